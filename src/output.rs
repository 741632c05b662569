//! The one way snapback writes a file (a scenario, a figure, the explorer's exports), so that writing
//! never destroys what is at the path:
//!
//! - `-` is standard output;
//! - a symlink is written through, to its target;
//! - a device, a FIFO or a socket (`/dev/null`, a named pipe, `/dev/stdout`) is written directly, never
//!   replaced by a regular file;
//! - a regular file is replaced atomically (a temporary file beside it, then a rename), keeping its
//!   permissions, and a read-only one only when the caller says so ([`Replace::Any`]);
//! - a new file is created the same way.

use std::fs::{self, File, OpenOptions, Permissions};
use std::io::{self, ErrorKind, Write};
use std::path::{Path, PathBuf};

/// Whether an existing read-only file may be replaced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Replace {
    /// Refuse ([`WriteError::ReadOnly`]): the user has not confirmed.
    Writable,
    /// Replace it (keeping it read-only): the user confirmed, e.g. with `--force`.
    Any,
}

/// Why nothing was written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    #[error("{} is read-only", path.display())]
    ReadOnly { path: PathBuf },
    #[error("{} is a directory", path.display())]
    Directory { path: PathBuf },
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: io::Error,
    },
}

/// How many symlinks a path may pass through (as Linux's own limit).
const MAX_LINKS: usize = 40;

/// Writes `bytes` to `path` (`-`: standard output) as described in the module's doc.
pub fn write(path: &Path, bytes: &[u8], replace: Replace) -> Result<(), WriteError> {
    if path == Path::new("-") {
        return to_stdout(bytes).map_err(|source| io_error(path, source));
    }
    let target = resolve(path).map_err(|source| io_error(path, source))?;
    match fs::metadata(&target) {
        Ok(meta) if meta.is_dir() => Err(WriteError::Directory { path: target }),
        Ok(meta) if !meta.is_file() || under_dev(path) => {
            direct(&target, bytes).map_err(|source| io_error(&target, source))
        }
        Ok(meta) => {
            if meta.permissions().readonly() && replace == Replace::Writable {
                return Err(WriteError::ReadOnly { path: target });
            }
            atomic(&target, bytes, Some(meta.permissions()))
                .map_err(|source| io_error(&target, source))
        }
        Err(e) if e.kind() == ErrorKind::NotFound => {
            atomic(&target, bytes, None).map_err(|source| io_error(&target, source))
        }
        Err(source) => Err(io_error(&target, source)),
    }
}

/// True for standard output (`-`) and an existing device, FIFO or socket: a destination written as a
/// stream, whose name says nothing of the format written to it.
pub fn is_stream(path: &Path) -> bool {
    path == Path::new("-") || fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

fn io_error(path: &Path, source: io::Error) -> WriteError {
    WriteError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Standard output; a closed pipe (`| head`) is not an error.
fn to_stdout(bytes: &[u8]) -> io::Result<()> {
    let mut out = io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

/// `/dev/stdout`, `/dev/fd/1` and the like name whatever the process has open, which may be a regular
/// file the shell opened (`> out.svg`, `>> log`): written directly, as a shell would.
fn under_dev(path: &Path) -> bool {
    path.starts_with("/dev") || path.starts_with("/proc")
}

/// The path at the end of `path`'s symlinks, the last of which may not exist yet. A link that the
/// kernel resolves itself (`/proc/self/fd/1`, behind `/dev/stdout`) is left to it.
fn resolve(path: &Path) -> io::Result<PathBuf> {
    let mut current = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        let is_link = fs::symlink_metadata(&current).is_ok_and(|m| m.file_type().is_symlink());
        if !is_link || fs::metadata(&current).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
            return Ok(current);
        }
        let link = fs::read_link(&current)?;
        current = match current.parent() {
            Some(dir) if link.is_relative() => dir.join(link),
            _ => link,
        };
    }
    Err(io::Error::other("too many levels of symbolic links"))
}

/// Writes into an existing special file as it is.
fn direct(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut file = OpenOptions::new().write(true).open(path)?;
    match file.write_all(bytes).and_then(|()| file.flush()) {
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

/// Writes a temporary file beside `path` and renames it over `path`, so that `path` is never left half
/// written; the new file gets `permissions` (an existing file's), or the default for a new file.
fn atomic(path: &Path, bytes: &[u8], permissions: Option<Permissions>) -> io::Result<()> {
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(ErrorKind::InvalidInput, "not a file name"))?;
    let mut temporary_name = std::ffi::OsString::from(".");
    temporary_name.push(name);
    temporary_name.push(format!(".{}.tmp", std::process::id()));
    let temporary = path.with_file_name(temporary_name);
    let written = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&temporary)
        .and_then(|mut file: File| {
            file.write_all(bytes)?;
            file.sync_all()?;
            if let Some(permissions) = permissions {
                file.set_permissions(permissions)?;
            }
            Ok(())
        })
        .and_then(|()| fs::rename(&temporary, path));
    if written.is_err() {
        let _ = fs::remove_file(&temporary);
    }
    written
}

#[cfg(test)]
mod tests {
    use std::os::unix::fs::{PermissionsExt, symlink};

    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("snapback-output-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_new_file_is_created_and_a_regular_one_replaced_keeping_its_mode() {
        let dir = scratch("regular");
        let path = dir.join("a.txt");
        write(&path, b"one", Replace::Writable).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"one");
        fs::set_permissions(&path, Permissions::from_mode(0o640)).unwrap();
        write(&path, b"two", Replace::Writable).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"two");
        let mode = fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o640);
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 1, "no temporary left");
    }

    #[test]
    fn a_symlink_is_written_through_even_when_its_target_is_missing() {
        let dir = scratch("link");
        let target = dir.join("target.txt");
        let link = dir.join("link.txt");
        symlink("target.txt", &link).unwrap();
        write(&link, b"new", Replace::Writable).unwrap();
        assert!(
            fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(fs::read(&target).unwrap(), b"new");
        write(&link, b"again", Replace::Writable).unwrap();
        assert!(
            fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(fs::read(&target).unwrap(), b"again");
    }

    #[test]
    fn a_read_only_file_is_kept_unless_replacing_it_is_confirmed() {
        let dir = scratch("readonly");
        let path = dir.join("r.txt");
        fs::write(&path, "keep").unwrap();
        fs::set_permissions(&path, Permissions::from_mode(0o444)).unwrap();
        let err = write(&path, b"lost", Replace::Writable).unwrap_err();
        assert!(matches!(err, WriteError::ReadOnly { .. }), "{err}");
        assert_eq!(err.to_string(), format!("{} is read-only", path.display()));
        assert_eq!(fs::read(&path).unwrap(), b"keep");
        write(&path, b"forced", Replace::Any).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"forced");
        assert!(fs::metadata(&path).unwrap().permissions().readonly());
    }

    #[test]
    fn a_device_is_written_into_not_replaced() {
        write(Path::new("/dev/null"), b"nothing", Replace::Writable).unwrap();
        let meta = fs::metadata("/dev/null").unwrap();
        assert!(!meta.is_file(), "/dev/null is still a device");
    }

    #[test]
    fn a_directory_is_refused() {
        let dir = scratch("dir");
        let err = write(&dir, b"x", Replace::Any).unwrap_err();
        assert!(matches!(err, WriteError::Directory { .. }), "{err}");
    }
}
