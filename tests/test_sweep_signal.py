"""The sweep view keeps its own state apart from Textual's: it once wrote `self._running`, which
is MessagePump's own flag, so after a sweep ended the screen counted as not running and a Signal
published to it delivered nothing (issue 42 item 2)."""

from textual.signal import Signal

from gearhead.tui.app import GearheadApp
from tests.test_sweep_screen import SIZE, open_sweep


async def test_a_signal_reaches_the_sweep_screen_after_a_sweep():
    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_sweep(pilot, "gear_ratio", "radius")
        assert screen.result is not None and screen.result.points  # the sweep ran and ended
        assert screen.is_running
        received = []
        signal: Signal[int] = Signal(app, "test-signal")
        signal.subscribe(screen, received.append)
        signal.publish(42)
        await pilot.pause()  # delivered once the screen's queued messages are processed
        assert received == [42]
