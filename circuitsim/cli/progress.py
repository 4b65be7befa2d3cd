"""Progress on a terminal: a tqdm bar on stderr when it is a tty, nothing otherwise.

tqdm (a dependency) draws the bar, rates and ETA; a pipe or a log file gets no carriage-return
noise. Every long verb (run, sweep, fit, diagnose) takes its callback from here.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any


def _width() -> int:
    # a terminal that reports 0 columns (some pseudo-terminals) would get an empty bar
    import shutil

    return shutil.get_terminal_size().columns


def enabled(quiet: bool = False) -> bool:
    """Draw bars only for a person watching: stderr is a terminal and --quiet was not given."""
    return not quiet and sys.stderr.isatty()


@contextmanager
def time_bar(stop: float, quiet: bool = False) -> Iterator[Callable[[float], None] | None]:
    """A bar over simulated time [s]; yields the ``progress(t)`` callback (None: no bar)."""
    if not enabled(quiet):
        yield None
        return
    from tqdm import tqdm

    with tqdm(total=stop, unit="s", desc="simulated", file=sys.stderr, ncols=_width(),
              leave=False, bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.4g}/{total:.4g} s "
              "[{elapsed}<{remaining}]") as bar, _ticking(bar):
        def update(t: float) -> None:
            bar.update(max(0.0, min(t, stop) - bar.n))

        yield update


@contextmanager
def _ticking(bar) -> Iterator[None]:
    """Redraw ``bar`` every second: the integrator reports only at waveform corners and
    every 50 000 output points, and a bar whose clock stands still looks like a hang."""
    import threading

    done = threading.Event()

    def tick() -> None:
        while not done.wait(1.0):
            bar.refresh()

    thread = threading.Thread(target=tick, daemon=True)
    thread.start()
    try:
        yield
    finally:
        done.set()
        thread.join(timeout=2)


@contextmanager
def count_bar(total: int, desc: str, quiet: bool = False
              ) -> Iterator[Callable[[int, int, dict], None] | None]:
    """A bar over runs; yields the sweep's ``progress(done, total, row)`` callback."""
    if not enabled(quiet):
        yield None
        return
    from tqdm import tqdm

    with tqdm(total=total, desc=desc, unit="run", file=sys.stderr, ncols=_width(), leave=False) as bar:
        def update(done: int, total_: int, row: dict[str, Any]) -> None:
            bar.total = total_
            bar.set_postfix_str(f"last: {row.get('status', '')}", refresh=False)
            bar.update(done - bar.n)

        yield update


@contextmanager
def status_line(desc: str, quiet: bool = False) -> Iterator[Callable[[str], None] | None]:
    """An open-ended bar (elapsed time and steps) whose text is the last message; yields the
    ``progress(message)`` callback the diagnosis and the fit accept (None: no terminal)."""
    if not enabled(quiet):
        yield None
        return
    from tqdm import tqdm

    with tqdm(desc=desc, unit="step", file=sys.stderr, ncols=_width(), leave=False,
              bar_format="{desc}: {n} steps [{elapsed}] {postfix}") as bar, _ticking(bar):
        def update(message: str) -> None:
            bar.set_postfix_str(str(message)[:60], refresh=False)
            bar.update(1)

        yield update
