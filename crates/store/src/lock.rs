//! One process per output: an exclusive `flock` on `OUT.h5.lock`, taken before anything of
//! the output (the file, `.partial`, the journal, spill files) is touched.
//!
//! Why `flock` on a file beside the output: the kernel drops the lock when the process
//! ends, however it ends (`kill -9`, a crash, a power loss), so a dead run never leaves a
//! stale lock behind. HDF5's own file locks come too late: by the time the second run's
//! library refuses the file it has already replaced the journal or the `.partial`.
//!
//! The lock file holds one line naming its holder (`pid`, `host`, `started`), for the
//! refusal message. It is removed when the lock is released; a taker that finds the path
//! replaced while it waited checks again, so removing it is safe.
//!
//! A symbolic link planted at `OUT.h5.lock` is never followed (`O_NOFOLLOW`: its target
//! would be truncated). Where the file system does not support `flock` (Lustre mounted
//! without `flock`, some NFS: `ENOLCK`, `ENOSYS`, `EOPNOTSUPP`), the run goes on without the
//! lock, as Cargo and HDF5 do there, and the lock says so ([`OutputLock::warning`]).

use std::fs::{File, OpenOptions};
use std::io::{Read, Seek, SeekFrom, Write};
use std::os::unix::fs::{MetadataExt, OpenOptionsExt};
use std::os::unix::io::AsRawFd;
use std::path::{Path, PathBuf};

/// The lock file of an output: `OUT.h5.lock`.
pub fn lock_path(output: &Path) -> PathBuf {
    let mut s = output.as_os_str().to_owned();
    s.push(".lock");
    PathBuf::from(s)
}

/// Held while this process owns the output; released (and the lock file removed) on drop.
#[derive(Debug)]
pub struct OutputLock {
    file: File,
    path: PathBuf,
    /// Set when the file system could not lock: the run is not protected from a second one.
    warning: Option<String>,
}

/// Why the lock was not taken.
#[derive(Debug)]
pub enum LockError {
    /// Another live process holds it.
    Held {
        output: PathBuf,
        lock_file: PathBuf,
        /// The holder's line (`pid=… host=… started=…`), when it could be read.
        holder: Option<String>,
    },
    /// The lock file could not be created or locked.
    Io { lock_file: PathBuf, error: String },
}

impl std::fmt::Display for LockError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LockError::Held {
                output,
                lock_file,
                holder,
            } => write!(
                f,
                "{} is in use by another batstudy process ({}); nothing was changed. Wait for it to finish, or stop it (its finished points are kept: --resume continues them). Lock file: {}",
                output.display(),
                holder
                    .as_deref()
                    .filter(|h| !h.is_empty())
                    .unwrap_or("holder unknown"),
                lock_file.display()
            ),
            LockError::Io { lock_file, error } => {
                write!(f, "cannot lock {}: {error}", lock_file.display())
            }
        }
    }
}

impl std::error::Error for LockError {}

/// This process, as the lock file names it.
fn holder_line() -> String {
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .or_else(|_| std::fs::read_to_string("/etc/hostname"))
        .map(|s| s.trim().to_string())
        .unwrap_or_default();
    format!(
        "pid={} host={} started={}",
        std::process::id(),
        if host.is_empty() { "unknown" } else { &host },
        super::iso8601_now()
    )
}

/// `flock(fd, LOCK_EX | LOCK_NB)`.
fn flock_exclusive(fd: std::os::unix::io::RawFd) -> std::io::Result<()> {
    // SAFETY: flock on a descriptor the caller owns; no memory is shared with the call.
    match unsafe { libc::flock(fd, libc::LOCK_EX | libc::LOCK_NB) } {
        0 => Ok(()),
        _ => Err(std::io::Error::last_os_error()),
    }
}

/// Errors by which a file system says it has no `flock` (not that the file is locked).
fn flock_unsupported(e: &std::io::Error) -> bool {
    matches!(
        e.raw_os_error(),
        Some(libc::ENOLCK | libc::ENOSYS | libc::EOPNOTSUPP | libc::EINVAL)
    )
}

impl OutputLock {
    /// Take the lock of `output` without waiting. The output's folder must exist.
    pub fn acquire(output: &Path) -> Result<OutputLock, LockError> {
        Self::acquire_with(output, flock_exclusive)
    }

    /// [`Self::acquire`] with the `flock` call given (tests give one that fails as a file
    /// system without locks does).
    fn acquire_with(
        output: &Path,
        flock: fn(std::os::unix::io::RawFd) -> std::io::Result<()>,
    ) -> Result<OutputLock, LockError> {
        let path = lock_path(output);
        let io = |e: std::io::Error| LockError::Io {
            lock_file: path.clone(),
            error: e.to_string(),
        };
        // A holder removes the file as it releases; if the path we locked was removed or
        // replaced meanwhile, our lock guards nothing: open the new file and try again.
        for _ in 0..100 {
            let mut file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .custom_flags(libc::O_NOFOLLOW)
                .open(&path)
                .map_err(|e| match e.raw_os_error() {
                    Some(libc::ELOOP) => io(std::io::Error::other(
                        "it is a symbolic link, which batstudy never follows (remove it)",
                    )),
                    _ => io(e),
                })?;
            let mut warning = None;
            if let Err(err) = flock(file.as_raw_fd()) {
                if flock_unsupported(&err) {
                    warning = Some(format!(
                        "this file system cannot lock {} ({err}): running without the lock, so nothing stops a second run on the same output",
                        path.display()
                    ));
                } else if err.raw_os_error() == Some(libc::EWOULDBLOCK) {
                    let mut holder = String::new();
                    let _ = file.read_to_string(&mut holder);
                    return Err(LockError::Held {
                        output: output.to_path_buf(),
                        lock_file: path,
                        holder: Some(holder.trim().to_string()),
                    });
                } else {
                    return Err(io(err));
                }
            }
            let same = match (file.metadata(), std::fs::metadata(&path)) {
                (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
                _ => false,
            };
            if !same {
                continue;
            }
            file.set_len(0).map_err(io)?;
            file.seek(SeekFrom::Start(0)).map_err(io)?;
            file.write_all(format!("{}\n", holder_line()).as_bytes())
                .map_err(io)?;
            return Ok(OutputLock {
                file,
                path,
                warning,
            });
        }
        Err(io(std::io::Error::other(
            "the lock file kept being replaced",
        )))
    }

    /// The lock file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Why this lock protects nothing (the file system has no `flock`), if it does not.
    pub fn warning(&self) -> Option<&str> {
        self.warning.as_deref()
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        // Removed while still locked: a waiting taker then sees a replaced path and retries.
        let _ = std::fs::remove_file(&self.path);
        // SAFETY: unlocking our own descriptor (closing it would too).
        unsafe { libc::flock(self.file.as_raw_fd(), libc::LOCK_UN) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // flock(2): "a call to flock() may block if an incompatible lock is held by another
    // process" — and by another open file description in the same process, which is what
    // these tests use (each acquire opens the file anew).
    #[test]
    fn second_taker_is_refused_and_named_the_holder() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("x.h5");
        let first = OutputLock::acquire(&out).unwrap();
        let second = OutputLock::acquire(&out).unwrap_err();
        match &second {
            LockError::Held { holder, .. } => {
                let h = holder.as_deref().unwrap();
                assert!(h.contains(&format!("pid={}", std::process::id())), "{h}");
                assert!(h.contains("host=") && h.contains("started="), "{h}");
            }
            e => panic!("{e}"),
        }
        let msg = second.to_string();
        assert!(msg.contains(&out.display().to_string()), "{msg}");
        drop(first);
        assert!(!lock_path(&out).exists(), "released lock leaves no file");
        let third = OutputLock::acquire(&out).unwrap();
        assert!(lock_path(&out).exists());
        drop(third);
    }

    // a symlink planted at OUT.h5.lock is refused, not followed, and its target kept whole
    #[test]
    fn a_symlink_at_the_lock_is_refused_and_its_target_kept() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("x.h5");
        let victim = dir.path().join("victim.txt");
        std::fs::write(&victim, "precious").unwrap();
        std::os::unix::fs::symlink(&victim, lock_path(&out)).unwrap();
        let e = OutputLock::acquire(&out).unwrap_err();
        assert!(e.to_string().contains("symbolic link"), "{e}");
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    }

    // where the file system has no flock (ENOLCK on NFS, ENOSYS on Lustre without
    // `-o flock`), the run goes on with a warning instead of failing outright; a held lock
    // (EWOULDBLOCK) is still a refusal and other errors still fail
    #[test]
    fn no_flock_on_the_file_system_is_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("x.h5");
        type Flock = fn(std::os::unix::io::RawFd) -> std::io::Result<()>;
        let unsupported: [Flock; 3] = [
            |_| Err(std::io::Error::from_raw_os_error(libc::ENOLCK)),
            |_| Err(std::io::Error::from_raw_os_error(libc::ENOSYS)),
            |_| Err(std::io::Error::from_raw_os_error(libc::EOPNOTSUPP)),
        ];
        for flock in unsupported {
            let lock = OutputLock::acquire_with(&out, flock).unwrap();
            assert!(lock.warning().unwrap().contains("without the lock"));
        }
        let held = OutputLock::acquire_with(&out, |_| {
            Err(std::io::Error::from_raw_os_error(libc::EWOULDBLOCK))
        });
        assert!(matches!(held, Err(LockError::Held { .. })));
        let io =
            OutputLock::acquire_with(&out, |_| Err(std::io::Error::from_raw_os_error(libc::EIO)));
        assert!(matches!(io, Err(LockError::Io { .. })));
        assert!(OutputLock::acquire(&out).unwrap().warning().is_none());
    }
}
