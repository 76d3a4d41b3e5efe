"""An interrupt that lands inside a garbage-collector callback is neither printed nor lost."""

from __future__ import annotations

import gc
import sys

import pytest

from sgplan.runtime.process import interrupts_handled, raise_swallowed_interrupt


class _InterruptedWhileFreed:
    """Raises KeyboardInterrupt when freed, as when Ctrl-C arrives while a ``__del__`` or weakref callback
    runs: Python cannot propagate it from there and hands it to ``sys.unraisablehook``."""

    def __del__(self) -> None:
        raise KeyboardInterrupt


def _swallow_one() -> None:
    _InterruptedWhileFreed()  # freed at once by reference counting
    gc.collect()


def test_a_swallowed_interrupt_is_kept_silently_and_raised_at_the_next_check(
    capsys: pytest.CaptureFixture[str],
) -> None:
    with pytest.raises(KeyboardInterrupt), interrupts_handled(termination=False, hold_after=False):
        _swallow_one()
        steps = 1  # the code after the swallowed interrupt runs on, as Python does
        raise_swallowed_interrupt()
        steps += 1
    assert steps == 1
    assert "Exception ignored" not in capsys.readouterr().err


def test_a_block_that_ends_after_a_swallowed_interrupt_raises_it_at_its_end() -> None:
    with pytest.raises(KeyboardInterrupt), interrupts_handled(termination=False, hold_after=False):
        _swallow_one()
    raise_swallowed_interrupt()  # nothing is left over for a later block


def test_other_unraisable_errors_and_the_hook_outside_the_block_are_untouched() -> None:
    seen: list[type[BaseException]] = []
    previous = sys.unraisablehook
    sys.unraisablehook = lambda unraisable: seen.append(type(unraisable.exc_value))
    try:
        class Failing:
            def __del__(self) -> None:
                raise ValueError("a bug in a finaliser")

        with interrupts_handled(termination=False, hold_after=False):
            Failing()
        assert seen == [ValueError]
        _swallow_one()
        assert seen == [ValueError, KeyboardInterrupt]  # outside the block: Python's own handling
    finally:
        sys.unraisablehook = previous
