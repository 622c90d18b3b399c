"""The command line's sharing commands (DESIGN.md "Command line"): `gearhead share FILE` prints a
preset's share code, `gearhead import TEXT` turns a share code or a ReCalc link into a preset,
`gearhead serve` runs the app in a browser (tui/serve.py).
Kept apart from cli.py, which registers them (`add_parsers`) and runs them (`run`)."""

from __future__ import annotations

import sys

from gearhead.core.errors import InputError, printable

COMMANDS = ("share", "import", "serve")


def add_parsers(sub) -> None:
    from . import serve

    sh = sub.add_parser("share", help="print a preset as a share code (gh1:…), accepted wherever a preset is")
    sh.add_argument("preset", metavar="FILE", help="a preset file (or a share code or ReCalc link)")
    sh.add_argument(
        "--link",
        metavar="BASE",
        nargs="?",
        const="gearhead://open",
        help="print a link carrying the code (default gearhead://open; or a served app's URL)",
    )
    im = sub.add_parser("import", help="a ReCalc link or a share code as a Gearhead preset (TOML)")
    im.add_argument("text", metavar="LINK", help="a reca.lc link (linear, arm, flywheel, ...) or a gh1: code")
    im.add_argument("--code", action="store_true", help="print a share code instead of the TOML")
    im.add_argument("--out", metavar="FILE", help="write the preset to FILE (never overwritten)")
    serve.add_parser(sub)


def run(args) -> int:
    if args.command == "serve":
        from . import serve

        return serve.run(args)
    if args.command == "share":
        return _share(args)
    return _import(args)


def _load(text: str):
    from gearhead.core import share

    if not text.strip():
        raise InputError("preset", "is empty; give a preset file, a share code or a ReCalc link")
    return share.load_any(text)


def _share(args) -> int:
    from gearhead.core import share

    preset = _load(args.preset)
    for warning in preset.warnings:
        print(f"gearhead: warning: {printable(warning)}", file=sys.stderr)  # may quote the file
    code = share.encode(preset)
    print(share.link(code, args.link) if args.link else code)
    return 0


def _import(args) -> int:
    import tomli_w

    from gearhead.core import presets, share

    preset = _load(args.text)
    for warning in preset.warnings:  # what a ReCalc link held that Gearhead has no field for
        print(f"gearhead: note: {printable(warning)}", file=sys.stderr)
    if args.code:
        print(share.encode(preset))
        return 0
    if args.out is None:
        sys.stdout.write(tomli_w.dumps(preset.as_toml()))
        return 0
    path = presets.save(preset, args.out, field="--out")  # refuses an existing file
    # a name is shown escaped, as `presets` lists it: a shared code's could hold an escape sequence
    print(
        f"{printable(preset.name)} ({printable(preset.calculator)}): preset written to {printable(path)}",
        file=sys.stderr,
    )
    return 0
