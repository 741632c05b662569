//! Whether the terminal can show Unicode, decided as tmux decides it: the first of LC_ALL, LC_CTYPE and
//! LANG that is set and not empty names a UTF-8 character set (`UTF-8` or `UTF8`, in any case). Unset,
//! or `C` and `POSIX`, it does not.

/// True when the locale in `var` (an environment lookup) is UTF-8.
pub fn utf8(var: impl Fn(&str) -> Option<String>) -> bool {
    ["LC_ALL", "LC_CTYPE", "LANG"]
        .into_iter()
        .find_map(|name| var(name).filter(|v| !v.is_empty()))
        .is_some_and(|locale| {
            let locale = locale.to_ascii_lowercase();
            locale.contains("utf-8") || locale.contains("utf8")
        })
}

/// True when this process's locale is UTF-8.
pub fn utf8_here() -> bool {
    utf8(|name| std::env::var(name).ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with(vars: &[(&str, &str)]) -> bool {
        utf8(|name| {
            vars.iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        })
    }

    #[test]
    fn the_first_set_variable_decides() {
        assert!(with(&[("LANG", "en_GB.UTF-8")]));
        assert!(with(&[("LC_CTYPE", "C.utf8"), ("LANG", "C")]));
        assert!(!with(&[("LC_ALL", "C"), ("LANG", "en_GB.UTF-8")]));
        assert!(with(&[("LC_ALL", ""), ("LANG", "en_GB.UTF-8")]));
        assert!(!with(&[("LANG", "POSIX")]));
        assert!(!with(&[]));
    }
}
