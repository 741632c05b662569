//! Reading a small text input, a scenario: from a file, or from standard input when the path is `-`.
//! Reads are bounded, and anything but a regular file (a FIFO, a device, a directory) is refused
//! before it is opened, so a read never blocks or runs without end.

use std::io::{self, Read};
use std::path::Path;

/// The most bytes read from one input: a scenario is a few lines of TOML.
pub const MAX_BYTES: u64 = 1 << 20;

/// The path that means standard input.
pub const STDIN: &str = "-";

/// The name errors give standard input.
pub const STDIN_NAME: &str = "<stdin>";

/// True when `path` means standard input.
pub fn is_stdin(path: &Path) -> bool {
    path.as_os_str() == STDIN
}

/// The text of `path` (standard input for `-`), at most [`MAX_BYTES`] of UTF-8.
pub fn read_text(path: &Path) -> io::Result<String> {
    if is_stdin(path) {
        return read_bounded(io::stdin().lock());
    }
    let kind = std::fs::metadata(path)?.file_type();
    if !kind.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "not a regular file but {}; give a file, or - for standard input",
                describe(kind)
            ),
        ));
    }
    read_bounded(std::fs::File::open(path)?)
}

/// At most [`MAX_BYTES`] of UTF-8 from `source`; more is an error.
fn read_bounded(source: impl Read) -> io::Result<String> {
    let mut bytes = Vec::new();
    source.take(MAX_BYTES + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_BYTES {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("larger than {MAX_BYTES} bytes (1 MiB), more than a scenario can be"),
        ));
    }
    String::from_utf8(bytes)
        .map_err(|_| io::Error::new(io::ErrorKind::InvalidData, "not UTF-8 text"))
}

/// What kind of file `kind` is, for a message.
fn describe(kind: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a FIFO";
        }
        if kind.is_char_device() {
            return "a character device";
        }
        if kind.is_block_device() {
            return "a block device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    if kind.is_dir() {
        "a directory"
    } else {
        "a special file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_up_to_the_bound_and_refuses_more() {
        let limit = MAX_BYTES as usize;
        assert_eq!(read_bounded(&vec![b'a'; limit][..]).unwrap().len(), limit);
        let err = read_bounded(io::repeat(b'a')).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidData);
        assert!(err.to_string().starts_with("larger than 1048576 bytes"));
        let err = read_bounded(&[0xff, 0xfe][..]).unwrap_err();
        assert_eq!(err.to_string(), "not UTF-8 text");
    }

    #[test]
    fn refuses_directories_and_devices_before_reading() {
        let err = read_text(Path::new(".")).unwrap_err();
        assert!(err.to_string().contains("a directory"), "{err}");
        #[cfg(unix)]
        {
            let err = read_text(Path::new("/dev/zero")).unwrap_err();
            assert!(err.to_string().contains("a character device"), "{err}");
        }
    }
}
