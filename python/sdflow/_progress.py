"""Progress of `Flow.advance`, `run` and `resume`: tqdm when installed, else a line on stderr."""

import math
import sys
import time


class _Silent:
    def update(self, step):
        pass

    def close(self):
        pass


class _Callable(_Silent):
    def __init__(self, function):
        self._function = function

    def update(self, step):
        self._function(step)


class _Bar(_Silent):
    """Fraction of the time or steps to go, the way `sdflow run` measures it."""

    def __init__(self, t_start, t_end, steps):
        self._t0, self._t_end = t_start, t_end
        self._steps, self._done = steps, 0
        self._tqdm = None
        self._last = 0.0
        try:
            from tqdm.auto import tqdm
            self._tqdm = tqdm(total=1000, unit="‰", leave=True,
                              bar_format="{l_bar}{bar}| {elapsed}<{remaining} {postfix}")
        except ImportError:
            pass

    def _fraction(self, step):
        f = 0.0
        if self._steps:
            f = self._done / self._steps
        if math.isfinite(self._t_end) and self._t_end > self._t0:
            f = max(f, (step.time - self._t0) / (self._t_end - self._t0))
        return min(f, 1.0)

    def update(self, step):
        self._done += 1
        f = self._fraction(step)
        if self._tqdm is not None:
            self._tqdm.n = int(1000 * f)
            self._tqdm.set_postfix_str(f"step {step.step} t={step.time:.6g} τ={step.tau:.3g}", refresh=True)
            return
        now = time.monotonic()
        if now - self._last >= 0.5 or f >= 1.0:
            self._last = now
            sys.stderr.write(f"\r{100 * f:5.1f}% step {step.step} t={step.time:.6g} τ={step.tau:.3g}\033[K")
            sys.stderr.flush()

    def close(self):
        if self._tqdm is not None:
            self._tqdm.close()
        elif self._done:
            sys.stderr.write("\n")


def make_progress(progress, t_start=0.0, t_end=math.inf, steps=None):
    """None/False: nothing; True: a bar; a callable: called with every Step."""
    if not progress:
        return _Silent()
    if callable(progress):
        return _Callable(progress)
    return _Bar(t_start, t_end, steps)
