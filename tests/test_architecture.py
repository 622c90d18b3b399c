"""core is pure: it never imports textual, rich or the app (DESIGN.md layout rule); and the
distribution installs one import package, gearhead (gearhead.core, gearhead.tui, gearhead.presets)."""

import ast
import pathlib
import subprocess
import sys

CORE = pathlib.Path(__file__).resolve().parents[1] / "core"
FORBIDDEN = ("textual", "rich", "tui", "gearhead.tui")


def _forbidden(module: str) -> bool:
    return any(module == f or module.startswith(f + ".") for f in FORBIDDEN)


def test_core_sources_never_import_the_ui():
    offenders = []
    for path in CORE.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                names = [node.module or ""]
            elif isinstance(node, ast.ImportFrom) and node.level >= 2:  # from ..tui (gearhead.tui)
                names = [("tui." + (node.module or "")) if (node.module or "").startswith("tui") else ""]
            else:
                continue
            offenders += [f"{path.name}: {n}" for n in names if n and _forbidden(n)]
    assert offenders == []


def test_solving_every_calculator_loads_no_ui_module():
    code = (
        "import sys\n"
        "from gearhead.core.registry import calculators\n"
        "from gearhead.core.model import solve\n"
        "for cid in calculators(): solve(cid, {})\n"
        "bad = sorted(m for m in sys.modules if m.split('.')[0] in {'textual', 'rich', 'tui'} "
        "or m.startswith('gearhead.tui'))\n"
        "print(','.join(bad))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=CORE.parent, check=True
    )
    assert out.stdout.strip() == ""


def test_every_package_folder_is_installed_under_gearhead():
    import tomllib

    root = CORE.parent
    config = tomllib.loads((root / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]
    listed = set(config["packages"])
    found = {
        "gearhead." + ".".join(p.parent.relative_to(root).parts)
        for top in ("core", "tui", "presets", "examples")
        for p in (root / top).rglob("__init__.py")
    }
    assert listed == found, "pyproject.toml [tool.setuptools] packages must list every package folder"
    assert all(name.startswith("gearhead.") for name in listed)


def test_the_installed_distribution_puts_only_gearhead_at_the_top():
    import sysconfig
    from importlib.metadata import distributions

    # the copy pip installed in site-packages (a build may leave gearhead.egg-info in the checkout)
    installed = [
        d for d in distributions(path=[sysconfig.get_paths()["purelib"]]) if d.metadata["Name"] == "gearhead"
    ]
    assert len(installed) == 1
    tops = {f.parts[0] for f in installed[0].files or ()}
    # '..' is the console script in bin/; __editable__* and a .pth only in an editable install
    stray = {
        t
        for t in tops
        if t not in ("gearhead", "..", "__pycache__")
        and not t.endswith((".dist-info", ".pth"))
        and not t.startswith("__editable__")
    }
    assert "gearhead" in tops or any(t.startswith("__editable__") for t in tops)
    assert stray == set()
