//! SIGINT and SIGTERM end `swm` without leaving files behind: a thread
//! waits for either, removes the temporary files of outputs being written
//! (`swm::io::discard_unfinished`, which also keeps any write from
//! starting or finishing meanwhile), and exits with 128 + the signal's
//! number (130 for SIGINT, 143 for SIGTERM), as a shell reports a process
//! killed by it. Outputs are therefore left as they were, or complete.
//!
//! `signal-hook` does the signal handling: its handler only wakes the
//! thread, so the cleanup runs as ordinary code, not inside a handler.

/// Starts the thread. Without it (on other systems, or if the handlers
/// cannot be installed) the signals keep their default action.
#[cfg(unix)]
pub fn install() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
        return;
    };
    let _ = std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                clear_progress_line();
                swm::io::discard_unfinished(|| std::process::exit(128 + signal));
            }
        });
}

#[cfg(not(unix))]
pub fn install() {}

/// Wipes a progress line (see `progress`) from a terminal's stderr, so
/// that the shell's prompt does not follow a half-drawn spinner. Every
/// other line on stderr ends with its newline, so the line the cursor is
/// on holds progress or nothing.
#[cfg(unix)]
fn clear_progress_line() {
    use std::io::{IsTerminal as _, Write as _};
    let mut e = std::io::stderr();
    if e.is_terminal() {
        let _ = e.write_all(b"\r\x1b[2K");
        let _ = e.flush();
    }
}
