"""What pilot tests share: waiting until the app has finished solving and drawing, and reaching
a card's sheet (the form) and results list the way a user does."""

from __future__ import annotations

from gearhead.tui.components.calculator_tab import CalculatorTab


async def started(pilot) -> None:
    """Wait for the first card: the app draws its first frame without it (no calculator is
    imported before), and builds the card of the calculator on screen right after."""
    app = pilot.app
    for _ in range(500):
        if app.card_ready(app.current_calculator):
            return
        await pilot.pause()
    raise AssertionError(f"the {app.current_calculator} card was never built")


async def settle(pilot) -> None:
    """Wait until every card has solved its latest entries and its chart is drawn."""
    app = pilot.app
    await started(pilot)
    for _ in range(200):
        await pilot.pause()
        await app.workers.wait_for_complete()
        await pilot.pause()
        if not any(tab.busy for tab in app.query(CalculatorTab)):
            break
    await pilot.pause()  # plots draw after the results land
    await pilot.pause()


def card(app, calc_id: str | None = None) -> CalculatorTab:
    return app.query_one(f"#calc-{calc_id or app.current_calculator}", CalculatorTab)


KEY_NAMES = {" ": "space", ".": "full_stop", "-": "minus", "+": "plus", "/": "slash", "*": "asterisk"}


def keys_of(text: str) -> list[str]:
    """The keys that type `text` (pilot.press takes key names)."""
    return [KEY_NAMES.get(ch, ch) for ch in text]


async def type_into(pilot, name: str, text: str, calc_id: str | None = None, commit: bool = True) -> None:
    """Put the sheet's cursor on a field and type `text` over its value, as a user does (typing
    replaces a value), then Enter (commits and moves down) unless `commit` is False."""
    tab = card(pilot.app, calc_id)
    tab.sheet.focus()
    await pilot.pause()
    if tab.sheet.editing:
        tab.sheet.commit()
    assert tab.sheet.move_to_field(name), f"{name} is not a row shown on the {tab.calculator.id} sheet"
    if text:
        await pilot.press(*keys_of(text))
    else:
        await pilot.press("delete")
    if commit:
        await pilot.press("enter")
    await settle(pilot)


def shown_rows(tab: CalculatorTab) -> list[str]:
    """Names of the fields the sheet shows (the mode's and choices')."""
    return [f.name for f in tab.sheet.shown_fields]


async def toggle(pilot, name: str, option: str | None = None, calc_id: str | None = None) -> None:
    """Put the sheet's cursor on a yes/no row, or on one flag of a flags row (↓ from its first),
    and press Space, as a user does."""
    tab = card(pilot.app, calc_id)
    tab.sheet.focus()
    await pilot.pause()
    assert tab.sheet.move_to_field(name), f"{name} is not a row shown on the {tab.calculator.id} sheet"
    for _ in range(len(tab.sheet.stops)):
        if option is None or tab.sheet.current_stop.option == option:
            break
        await pilot.press("down")
    assert tab.sheet.current_stop.option == option, f"{name} has no flag {option}"
    await pilot.press("space")
    await settle(pilot)
