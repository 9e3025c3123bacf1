//! The commands' progress on stderr: a bar on a terminal; plain lines elsewhere (a batch
//! job's log), one when a new stage starts and one at least every
//! [`batch_interval`] seconds while a stage runs, each with the elapsed time and, where
//! the stage counts steps, the estimated time left; nothing when quiet.

use std::io::{IsTerminal, Write};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

/// Seconds between two progress lines off a terminal: `JOINTLIN_PROGRESS_SECONDS` when
/// set to a positive number, else 10.
pub fn batch_interval() -> Duration {
    std::env::var("JOINTLIN_PROGRESS_SECONDS")
        .ok()
        .and_then(|v| v.parse::<f64>().ok())
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .filter(|d| !d.is_zero())
        .unwrap_or(Duration::from_secs(10))
}

/// A command's progress: a stage (`message`) with `position` of `length` steps done.
pub struct Progress {
    inner: Inner,
}

enum Inner {
    Hidden,
    Bar(ProgressBar),
    Lines {
        shared: Arc<Shared>,
        ticker: Option<JoinHandle<()>>,
    },
}

/// What the line printer and its ticker thread share.
struct Shared {
    state: Mutex<Lines>,
    /// Set when the command is done; wakes the ticker.
    finished: (Mutex<bool>, Condvar),
    interval: Duration,
}

struct Lines {
    start: Instant,
    message: String,
    position: u64,
    length: u64,
    /// When the count last started over and its position then (for the time left).
    stage: (Instant, u64),
    printed: Option<Instant>,
}

/// The command's progress: hidden when `quiet`, a bar when stderr is a terminal, lines
/// otherwise.
pub fn progress_bar(quiet: bool) -> Progress {
    let inner = if quiet {
        Inner::Hidden
    } else if std::io::stderr().is_terminal() {
        let pb = ProgressBar::new(1);
        pb.set_style(
            ProgressStyle::with_template("{msg:40} [{bar:40}] {pos}/{len} {elapsed} (ETA {eta})")
                .expect("static template")
                .progress_chars("=> "),
        );
        Inner::Bar(pb)
    } else {
        let now = Instant::now();
        let shared = Arc::new(Shared {
            state: Mutex::new(Lines {
                start: now,
                message: String::new(),
                position: 0,
                length: 0,
                stage: (now, 0),
                printed: None,
            }),
            finished: (Mutex::new(false), Condvar::new()),
            interval: batch_interval(),
        });
        let ticking = Arc::clone(&shared);
        let ticker = std::thread::spawn(move || ticking.tick_until_finished());
        Inner::Lines {
            shared,
            ticker: Some(ticker),
        }
    };
    Progress { inner }
}

impl Progress {
    pub fn set_length(&self, length: u64) {
        match &self.inner {
            Inner::Hidden => {}
            Inner::Bar(pb) => pb.set_length(length),
            Inner::Lines { shared, .. } => shared.update(|l| l.length = length),
        }
    }

    pub fn set_position(&self, position: u64) {
        match &self.inner {
            Inner::Hidden => {}
            Inner::Bar(pb) => pb.set_position(position),
            Inner::Lines { shared, .. } => shared.update(|l| l.position = position),
        }
    }

    pub fn inc(&self, steps: u64) {
        match &self.inner {
            Inner::Hidden => {}
            Inner::Bar(pb) => pb.inc(steps),
            Inner::Lines { shared, .. } => shared.update(|l| l.position += steps),
        }
    }

    /// A new message starts a new stage (off a terminal a line at once, unless the last
    /// was printed less than a second ago).
    pub fn set_message(&self, message: &str) {
        match &self.inner {
            Inner::Hidden => {}
            Inner::Bar(pb) => pb.set_message(message.to_string()),
            Inner::Lines { shared, .. } => {
                let mut l = shared.state.lock().unwrap_or_else(|e| e.into_inner());
                if l.message != message {
                    l.message = message.to_string();
                    // At most a line a second when stages follow each other fast.
                    let gap = shared.interval.min(Duration::from_secs(1));
                    if l.printed.is_none_or(|t| t.elapsed() >= gap) {
                        print_line(&mut l);
                    }
                }
            }
        }
    }

    /// Ends the progress: the bar cleared, the line printer stopped.
    pub fn finish_and_clear(&mut self) {
        match &mut self.inner {
            Inner::Hidden => {}
            Inner::Bar(pb) => pb.finish_and_clear(),
            Inner::Lines { shared, ticker } => {
                let (done, wake) = &shared.finished;
                *done.lock().unwrap_or_else(|e| e.into_inner()) = true;
                wake.notify_all();
                if let Some(t) = ticker.take() {
                    let _ = t.join();
                }
            }
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish_and_clear();
    }
}

impl Shared {
    /// Applies `change`, then prints a line if the last is `interval` old. A count that
    /// starts over (a new length, or a position going back: the next pass or sweep)
    /// starts the stage's clock for the time left anew.
    fn update(&self, change: impl FnOnce(&mut Lines)) {
        let mut l = self.state.lock().unwrap_or_else(|e| e.into_inner());
        let (position, length) = (l.position, l.length);
        change(&mut l);
        if l.length != length || l.position < position {
            l.stage = (Instant::now(), l.position);
        }
        if !l.message.is_empty() && l.printed.is_none_or(|t| t.elapsed() >= self.interval) {
            print_line(&mut l);
        }
    }

    /// Prints a line whenever the last is `interval` old, also while nothing reports
    /// (a long factorization, the static step), until finished.
    fn tick_until_finished(&self) {
        let (done, wake) = &self.finished;
        let mut finished = done.lock().unwrap_or_else(|e| e.into_inner());
        while !*finished {
            let step = (self.interval / 4).max(Duration::from_millis(10));
            finished = wake
                .wait_timeout(finished, step)
                .unwrap_or_else(|e| e.into_inner())
                .0;
            if *finished {
                break;
            }
            let mut l = self.state.lock().unwrap_or_else(|e| e.into_inner());
            if !l.message.is_empty() && l.printed.is_none_or(|t| t.elapsed() >= self.interval) {
                print_line(&mut l);
            }
        }
    }
}

/// `[  12.3 s] MESSAGE: 40/273, about 18 s left` on stderr.
fn print_line(l: &mut Lines) {
    let elapsed = l.start.elapsed().as_secs_f64();
    let mut line = format!("[{elapsed:7.1} s] {}", l.message);
    if l.length > 0 {
        line += &format!(": {}/{}", l.position.min(l.length), l.length);
        let (since, from) = l.stage;
        let done = l.position.saturating_sub(from);
        if done > 0 && l.position < l.length {
            let per_step = since.elapsed().as_secs_f64() / done as f64;
            let left = per_step * (l.length - l.position) as f64;
            let digits = usize::from(left < 10.0);
            line += &format!(", about {left:.digits$} s left");
        }
    }
    let _ = writeln!(std::io::stderr(), "{line}");
    l.printed = Some(Instant::now());
}
