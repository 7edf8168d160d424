"""A progress line for work that may run long (the bootstrap of `rigid fragility` and `rigid
hazard`): nothing for the first few seconds, then a line every few seconds on stderr with a fixed
denominator (the fits the command will make), the share done, the time spent and an estimate of
the time left. On a terminal the line rewrites itself (carriage return); elsewhere (a log, a batch
job) each report is its own line.
"""
import math
import sys
import time


def clock_text(seconds):
    """0:42, 12:05, 1:02:03."""
    if not math.isfinite(seconds) or seconds < 0:
        return "--:--"
    t = int(round(seconds))
    return f"{t // 3600}:{t // 60 % 60:02d}:{t % 60:02d}" if t >= 3600 else f"{t // 60}:{t % 60:02d}"


class FitProgress:
    """Counts fits (each a maximum-likelihood fit with its bootstrap resamples) towards a total fixed
    at the start; fragility_fit calls resample() after each bootstrap resample and fit_done() after
    each fit."""

    def __init__(self, total_fits, label, after_s=5.0, every_s=5.0, stream=None, clock=time.monotonic):
        self.total = max(int(total_fits), 1)
        self.label = label
        self.after_s, self.every_s = after_s, every_s
        self.stream = stream if stream is not None else sys.stderr
        self.clock = clock
        self.start = clock()
        self.last = None  # time of the last line written, None before the first
        self.fits = 0
        self.within = 0.0  # share of the current fit's resamples done
        self.resamples = 0
        try:
            self.live = self.stream.isatty()
        except (AttributeError, ValueError):
            self.live = False

    def done(self):
        return min(self.fits + min(self.within, 1.0), self.total)

    def resample(self, replicates):
        self.resamples += 1
        self.within += 1.0 / max(replicates, 1)
        self._maybe_report()

    def fit_done(self):
        self.fits += 1
        self.within = 0.0
        self._maybe_report()

    def line(self, now):
        elapsed = now - self.start
        done = self.done()
        eta = elapsed * (self.total - done) / done if done > 0 else math.nan
        return (f"{self.label}: {done:.1f}/{self.total} fits ({100 * done / self.total:.0f} %), "
                f"{self.resamples} bootstrap resamples, {clock_text(elapsed)} elapsed, ETA {clock_text(eta)}")

    def _maybe_report(self):
        now = self.clock()
        if now - self.start < self.after_s or (self.last is not None and now - self.last < self.every_s):
            return
        self.last = now
        self._write(self.line(now))

    def _write(self, text):
        self.stream.write(f"\r{text}   " if self.live else text + "\n")
        self.stream.flush()

    def finish(self):
        """The closing line, only when a progress line was shown."""
        if self.last is None:
            return
        self._write(self.line(self.clock()).split(",")[0] + f", done in {clock_text(self.clock() - self.start)}")
        if self.live:
            self.stream.write("\n")
            self.stream.flush()
