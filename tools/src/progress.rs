//! Progress on stderr (indicatif) for commands that may run long: a
//! spinner with the elapsed time and the current phase for `encode`
//! (the encoder runs inside the library, which reports no progress, so
//! the phases are the CLI's own: reading, encoding, writing),
//! and a bar over the (mesh, rate, configuration) cells for `rd`.
//!
//! Nothing is drawn for a run that ends within [`DELAY`], when stderr is
//! not a terminal (a pipe, a file, a test harness), with `TERM=dumb`, or
//! with `--quiet`. Progress never goes to stdout, so results and
//! `--json` there are the same with and without it. A bar is cleared
//! from the terminal when it is dropped, before the command prints its
//! results, warnings or error line.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal as _;
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::Duration;

/// How long a run goes before its progress appears: shorter runs print
/// nothing to wipe.
pub const DELAY: Duration = Duration::from_secs(1);

/// How long a run goes before its progress is drawn: [`DELAY`], or
/// `SWM_PROGRESS_DELAY_MS` milliseconds when that is set (the tests set
/// 0, so that what they check does not depend on how fast the machine
/// runs the command).
fn delay() -> Duration {
    std::env::var("SWM_PROGRESS_DELAY_MS")
        .ok()
        .and_then(|v| v.parse().ok())
        .map_or(DELAY, Duration::from_millis)
}

/// Redraws per second of the spinner and the elapsed time.
const TICK: Duration = Duration::from_millis(100);

/// A spinner or a bar, hidden until [`DELAY`] has passed.
pub struct Progress {
    bar: ProgressBar,
    /// The thread that shows the bar after [`DELAY`]; dropping the sender
    /// wakes it early to leave the bar hidden.
    reveal: Option<(mpsc::Sender<()>, JoinHandle<()>)>,
}

impl Progress {
    /// A spinner with the elapsed time and a phase ([`Progress::phase`]),
    /// for work whose length is unknown: `swm encode [00:00:12] encoding`.
    pub fn spinner(quiet: bool) -> Progress {
        let style = ProgressStyle::with_template("{spinner} {prefix} [{elapsed_precise}] {msg}")
            .expect("a valid template");
        Progress::start(None, style, shows(quiet))
    }

    /// A bar over `len` steps: `swm rd [00:01:40] ====>---- 12/60 cells`.
    pub fn bar(len: u64, quiet: bool) -> Progress {
        let style =
            ProgressStyle::with_template("{prefix} [{elapsed_precise}] {bar:40} {pos}/{len} {msg}")
                .expect("a valid template");
        Progress::start(Some(len), style, shows(quiet))
    }

    /// A bar hidden from the start; when it may be `shown`, a thread
    /// draws it after [`DELAY`] unless the work is over by then.
    fn start(len: Option<u64>, style: ProgressStyle, shown: bool) -> Progress {
        Progress::start_after(len, style, shown, delay())
    }

    /// [`Progress::start`] with the delay given.
    fn start_after(
        len: Option<u64>,
        style: ProgressStyle,
        shown: bool,
        delay: Duration,
    ) -> Progress {
        let bar =
            ProgressBar::with_draw_target(len, ProgressDrawTarget::hidden()).with_style(style);
        let reveal = shown.then(|| {
            let (tx, rx) = mpsc::channel::<()>();
            let b = bar.clone();
            let handle = std::thread::spawn(move || {
                // Only the timeout reveals; a dropped sender (the work
                // ended) leaves the bar hidden.
                if let Err(mpsc::RecvTimeoutError::Timeout) = rx.recv_timeout(delay) {
                    b.set_draw_target(ProgressDrawTarget::stderr());
                    b.enable_steady_tick(TICK);
                }
            });
            (tx, handle)
        });
        Progress { bar, reveal }
    }

    /// Names what the command is doing now (for a bar: the unit after the
    /// count, such as `cells`).
    pub fn phase(&self, what: &'static str) {
        self.bar.set_message(what);
    }

    /// The command's name before the elapsed time (`swm encode`).
    pub fn prefix(self, name: &'static str) -> Progress {
        self.bar.set_prefix(name);
        self
    }

    /// Runs `f` (which prints) with the bar off the terminal.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    /// One more step of a bar done (safe from any thread).
    pub fn inc(&self) {
        self.bar.inc(1);
    }

    /// Whether anything is, or may yet be, drawn: false when quiet or when
    /// stderr is not a terminal.
    #[cfg(test)]
    fn may_show(&self) -> bool {
        self.reveal.is_some()
    }
}

/// Whether progress may be drawn at all: not with `--quiet`, and only
/// on a terminal.
fn shows(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

impl Drop for Progress {
    /// Stops the reveal thread (so that it cannot draw after this) and
    /// clears whatever was drawn.
    fn drop(&mut self) {
        if let Some((tx, handle)) = self.reveal.take() {
            drop(tx);
            let _ = handle.join();
        }
        self.bar.finish_and_clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quiet_never_shows() {
        let p = Progress::spinner(true).prefix("swm encode");
        p.phase("encoding");
        assert!(!p.may_show());
        assert!(p.bar.is_hidden());
        let b = Progress::bar(3, true);
        b.inc();
        assert!(!b.may_show());
        assert_eq!(b.bar.position(), 1);
    }

    /// A run shorter than the delay, where progress may be shown, ends
    /// with its bar never drawn, and drop returns at once (it wakes the
    /// reveal thread instead of waiting out the delay). The delay is an
    /// hour, so that a loaded machine cannot make the check flake: only a
    /// drop that waited it out takes anywhere near that.
    #[test]
    fn a_short_run_stays_hidden() {
        let hour = Duration::from_secs(3600);
        let start = std::time::Instant::now();
        let style = ProgressStyle::default_spinner();
        let p = Progress::start_after(None, style, true, hour);
        assert!(p.may_show());
        p.phase("reading");
        assert!(p.bar.is_hidden());
        drop(p);
        assert!(start.elapsed() < hour / 60, "{:?}", start.elapsed());
    }
}
