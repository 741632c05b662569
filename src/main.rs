use std::io::Write;
use std::process::ExitCode;

use clap::Parser;
use clap::error::ErrorKind;

fn main() -> ExitCode {
    match snapback::cli::Cli::try_parse() {
        Ok(cli) => snapback::cli::run(cli),
        Err(e) if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        Err(e) => {
            let args: Vec<String> = std::env::args_os()
                .map(|a| a.to_string_lossy().into_owned())
                .collect();
            let message = match snapback::cli::spaced_unit(&args) {
                Some(remedy) => format!("error: {remedy}"),
                None => format!("{} (see --help)", one_line(&e.render().to_string())),
            };
            let _ = writeln!(std::io::stderr(), "{message}");
            ExitCode::from(2)
        }
    }
}

/// Bad input is one line on stderr, as everywhere: clap's first line, which names the flag, and the
/// indented lines that qualify it (`[possible values: ...]`, `tip: ...`, the list a line ending in `:`
/// announces), without the usage.
fn one_line(text: &str) -> String {
    let mut lines = text.lines();
    let mut line = lines
        .next()
        .unwrap_or("error: invalid arguments")
        .to_string();
    let details: Vec<&str> = lines
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
        .filter(|l| l.starts_with(char::is_whitespace) && !l.trim().is_empty())
        .map(str::trim)
        .collect();
    if !details.is_empty() {
        line = if line.ends_with(':') {
            format!("{line} {}", details.join(", "))
        } else {
            format!("{line}; {}", details.join("; "))
        };
    }
    line
}
