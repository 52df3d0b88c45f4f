//! A spinner on standard error for a phase of work, shown only once the phase has run for a
//! second and only when standard error is a terminal (indicatif draws nothing otherwise), so
//! quick runs and piped or logged output stay clean.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::mpsc::{self, RecvTimeoutError, Sender};
use std::thread::JoinHandle;
use std::time::Duration;

/// How long a phase runs before its spinner appears.
const DELAY: Duration = Duration::from_secs(1);

/// A running phase; its spinner disappears when it is dropped.
pub struct Phase {
    bar: ProgressBar,
    done: Option<Sender<()>>,
    waiter: Option<JoinHandle<()>>,
}

impl Phase {
    /// Starts a phase described by `message` (for example "meshing the board").
    pub fn start(message: &str) -> Phase {
        let bar = ProgressBar::hidden();
        let style = ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_spinner());
        bar.set_style(style);
        bar.set_message(message.to_string());
        let (done, wait) = mpsc::channel::<()>();
        let shown = bar.clone();
        let waiter = std::thread::spawn(move || {
            if wait.recv_timeout(DELAY) == Err(RecvTimeoutError::Timeout) {
                shown.set_draw_target(ProgressDrawTarget::stderr());
                shown.enable_steady_tick(Duration::from_millis(120));
            }
        });
        Phase {
            bar,
            done: Some(done),
            waiter: Some(waiter),
        }
    }
}

impl Drop for Phase {
    fn drop(&mut self) {
        drop(self.done.take());
        if let Some(waiter) = self.waiter.take() {
            let _ = waiter.join();
        }
        self.bar.finish_and_clear();
    }
}
