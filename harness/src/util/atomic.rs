//! Atomic outputs. Every report file is written under a temporary name in its own
//! directory (`.NAME.partial`) and renamed into place once written and flushed to disk,
//! so a reader never sees a truncated file under a final name. `run.json` is written
//! last: it marks a complete run. [`begin`] removes an earlier run's marker before
//! anything is computed, so an interrupted or failed run leaves no marker behind, and
//! makes SIGINT/SIGTERM say so on stderr before the process ends (exit 130/143). A
//! signal that arrives while the marker is being renamed into place waits for the rename
//! (the run then ends normally: its outputs are complete); one that arrives after it says
//! the run is complete and exits 0.

use std::ffi::OsString;
use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicI32, AtomicU8, Ordering};
use std::sync::OnceLock;

/// The file written last; its presence marks a complete set of outputs.
pub const MARKER: &str = "run.json";

/// Suffix of a file being written; never the name of a finished output.
pub const PARTIAL_SUFFIX: &str = ".partial";

/// Message printed when SIGINT/SIGTERM ends the process (set once by [`begin`]).
static NOTICE: OnceLock<Vec<u8>> = OnceLock::new();
/// Message printed when a signal arrives after the marker is in place.
static COMPLETE_NOTICE: OnceLock<Vec<u8>> = OnceLock::new();

/// Where the marker is: not written ([`MARKER_ABSENT`]), being renamed into place, or in
/// place. Read by the signal handler (lock-free atomics are async-signal-safe).
static MARKER_STATE: AtomicU8 = AtomicU8::new(MARKER_ABSENT);
const MARKER_ABSENT: u8 = 0;
const MARKER_COMMITTING: u8 = 1;
const MARKER_IN_PLACE: u8 = 2;
/// A signal that arrived while the marker was being renamed (0: none).
static PENDING_SIGNAL: AtomicI32 = AtomicI32::new(0);

/// Prepares `dir` for a run's outputs: creates it, removes an earlier run's marker and
/// leftover `.partial` files, and installs the interrupt notice. Call before the run.
pub fn begin(dir: &Path) -> io::Result<()> {
    prepare(dir)?;
    let _ = NOTICE.set(
        format!(
            "\njointlin: interrupted; {} holds no complete run ({MARKER} is written last and is absent)\n",
            dir.display()
        )
        .into_bytes(),
    );
    let _ = COMPLETE_NOTICE.set(
        format!(
            "\njointlin: interrupted after the run was complete; {} holds it ({MARKER} written)\n",
            dir.display()
        )
        .into_bytes(),
    );
    MARKER_STATE.store(MARKER_ABSENT, Ordering::SeqCst);
    #[cfg(unix)]
    install_notice();
    Ok(())
}

/// Writes the marker `dir/`[`MARKER`] atomically ([`write_text`]), the last file of a
/// complete run. An interrupt during the rename is held until it is done; if the rename
/// failed, the held interrupt then ends the process as any other (exit 128 + signal).
pub fn write_marker(dir: &Path, text: &str) -> Result<PathBuf, String> {
    let path = dir.join(MARKER);
    MARKER_STATE.store(MARKER_COMMITTING, Ordering::SeqCst);
    let done = write_text(&path, text);
    let state = if done.is_ok() {
        MARKER_IN_PLACE
    } else {
        MARKER_ABSENT
    };
    MARKER_STATE.store(state, Ordering::SeqCst);
    let held = PENDING_SIGNAL.swap(0, Ordering::SeqCst);
    if held != 0 {
        #[cfg(unix)]
        on_signal(held);
    }
    done.map(|()| path)
}

/// Creates `dir` and removes an earlier run's marker and leftover `.partial` files.
pub fn prepare(dir: &Path) -> io::Result<()> {
    if dir.exists() && !dir.is_dir() {
        return Err(io::Error::other(
            "is a file, not a directory: --out names the directory the outputs go into",
        ));
    }
    std::fs::create_dir_all(dir)?;
    match std::fs::remove_file(dir.join(MARKER)) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => return Err(e),
        _ => {}
    }
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if name.starts_with('.') && name.ends_with(PARTIAL_SUFFIX) {
            std::fs::remove_file(entry.path())?;
        }
    }
    Ok(())
}

/// Temporary name of `path`: `.NAME.partial` beside it.
pub fn partial_path(path: &Path) -> PathBuf {
    let mut name = OsString::from(".");
    name.push(path.file_name().unwrap_or_default());
    name.push(PARTIAL_SUFFIX);
    path.with_file_name(name)
}

/// Runs `write` on the temporary name of `path`, then renames it to `path`. On any error
/// the temporary file is removed and `path` is left as it was; the message names `path`.
pub fn with_temp(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), String> {
    let tmp = partial_path(path);
    let done = write(&tmp).and_then(|()| {
        // The data reach the disk before the name does (a crash then never leaves a
        // short file under the final name).
        let sync = File::open(&tmp).and_then(|f| f.sync_all());
        sync.and_then(|()| std::fs::rename(&tmp, path))
            .map_err(|e| e.to_string())
    });
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done.map_err(|e| format!("{}: {e}", path.display()))
}

/// Writes `text` to `path` atomically ([`with_temp`]).
pub fn write_text(path: &Path, text: &str) -> Result<(), String> {
    with_temp(path, |tmp| {
        let mut f = File::create(tmp).map_err(|e| e.to_string())?;
        f.write_all(text.as_bytes())
            .and_then(|()| f.flush())
            .map_err(|e| e.to_string())
    })
}

#[cfg(unix)]
fn install_notice() {
    extern "C" {
        fn signal(signum: i32, handler: usize) -> usize;
    }
    const SIGINT: i32 = 2;
    const SIGTERM: i32 = 15;
    // SAFETY: signal(2) with valid signal numbers and a handler that only calls the
    // async-signal-safe write(2) and _exit(2).
    unsafe {
        signal(SIGINT, on_signal as *const () as usize);
        signal(SIGTERM, on_signal as *const () as usize);
    }
}

#[cfg(unix)]
extern "C" fn on_signal(signum: i32) {
    extern "C" {
        fn write(fd: i32, buf: *const u8, n: usize) -> isize;
        fn _exit(code: i32) -> !;
    }
    let (notice, code) = match MARKER_STATE.load(Ordering::SeqCst) {
        MARKER_COMMITTING => {
            // The rename finishes first; write_marker acts on the signal after it.
            PENDING_SIGNAL.store(signum, Ordering::SeqCst);
            return;
        }
        MARKER_IN_PLACE => (&COMPLETE_NOTICE, 0),
        _ => (&NOTICE, 128 + signum),
    };
    if let Some(msg) = notice.get() {
        // SAFETY: a valid buffer of msg.len() bytes; fd 2 is stderr.
        unsafe {
            write(2, msg.as_ptr(), msg.len());
        }
    }
    // SAFETY: _exit ends the process without running handlers (async-signal-safe).
    unsafe { _exit(code) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("jointlin-atomic-{}-{tag}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_failing_writer_leaves_the_old_file_and_no_partial() {
        let d = scratch("fail");
        let p = d.join("points.csv");
        std::fs::write(&p, "old\n").unwrap();
        // The writer fails after half its data (an injected full disk).
        let r = with_temp(&p, |tmp| {
            let mut f = File::create(tmp).unwrap();
            f.write_all(b"frequency_Hz,point\n1.0,").unwrap();
            Err("No space left on device".to_string())
        });
        assert!(r.unwrap_err().contains("points.csv: No space left"));
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old\n");
        assert!(!partial_path(&p).exists());
        write_text(&p, "new\n").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "new\n");
        assert!(!partial_path(&p).exists());
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn begin_removes_the_old_marker_and_partials() {
        let d = scratch("begin");
        std::fs::write(d.join(MARKER), "{}").unwrap();
        std::fs::write(d.join(".points.csv.partial"), "1,2").unwrap();
        std::fs::write(d.join("results.csv"), "kept\n").unwrap();
        prepare(&d).unwrap();
        assert!(!d.join(MARKER).exists());
        assert!(!d.join(".points.csv.partial").exists());
        assert!(d.join("results.csv").exists());
        std::fs::remove_dir_all(&d).unwrap();
    }
}
