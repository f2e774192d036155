//! Progress of a long run: a bar with percentage and ETA on a terminal, a
//! plain line every ten seconds otherwise (a log, CI), nothing for short
//! runs. The total comes from a model (pairs to decide, or the cycle
//! model's cycles), so the percentage is known from the start.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Seconds between two plain progress lines.
const PLAIN_PERIOD: Duration = Duration::from_secs(10);

pub struct Progress {
    bar: ProgressBar,
    plain: Option<Plain>,
}

struct Plain {
    total: u64,
    unit: &'static str,
    done: AtomicU64,
    started: Instant,
    last: Mutex<Instant>,
    /// The first report's count and time: the rate for the ETA is measured
    /// from there, past any build or set-up before the work began.
    first: Mutex<Option<(u64, Instant)>>,
}

impl Progress {
    /// Progress over `total` `unit`s; shown only when `total` reaches
    /// `threshold`.
    pub fn new(total: u64, unit: &'static str, threshold: u64) -> Progress {
        if total < threshold || total == 0 {
            return Progress {
                bar: ProgressBar::hidden(),
                plain: None,
            };
        }
        if !std::io::stderr().is_terminal() {
            let now = Instant::now();
            let plain = Plain {
                total,
                unit,
                done: AtomicU64::new(0),
                started: now,
                last: Mutex::new(now),
                first: Mutex::new(None),
            };
            return Progress {
                bar: ProgressBar::hidden(),
                plain: Some(plain),
            };
        }
        let bar = ProgressBar::new(total);
        if let Ok(style) = ProgressStyle::with_template(&format!("{{spinner}} {unit} [{{bar:40}}] {{human_pos}}/{{human_len}} ({{percent}} %, eta {{eta}})")) {
            bar.set_style(style.progress_chars("=> "));
        }
        Progress { bar, plain: None }
    }

    /// `n` more units done.
    pub fn inc(&self, n: u64) {
        self.bar.inc(n);
        let Some(plain) = &self.plain else { return };
        let done = plain.done.fetch_add(n, Ordering::Relaxed) + n;
        let first = match plain.first.lock() {
            Ok(mut first) => *first.get_or_insert((done, Instant::now())),
            Err(_) => return,
        };
        let Ok(mut last) = plain.last.try_lock() else {
            return;
        };
        if last.elapsed() < PLAIN_PERIOD {
            return;
        }
        *last = Instant::now();
        let fraction = (done as f64 / plain.total as f64).min(1.0);
        let rate = (done - first.0) as f64 / first.1.elapsed().as_secs_f64();
        let eta = if rate > 0.0 {
            format!("{:.0} s", plain.total.saturating_sub(done) as f64 / rate)
        } else {
            "unknown".into()
        };
        eprintln!(
            "progress: {:.0} % ({done} of {} {}), {:.0} s so far, eta {eta}",
            100.0 * fraction,
            plain.total,
            plain.unit,
            plain.started.elapsed().as_secs_f64(),
        );
    }

    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
