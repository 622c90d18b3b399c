"""The licence files ship with the distribution, and ReCalc's MIT notice travels with its data."""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_pyproject_names_the_licence_and_its_files():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert project["license"] == "MIT"
    assert set(project["license-files"]) == {"LICENSE", "THIRD_PARTY_NOTICES"}
    assert all((ROOT / name).is_file() for name in project["license-files"])
    assert not any(c.startswith("License ::") for c in project["classifiers"])  # PEP 639: the expression only


def test_the_licence_is_mit():
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License") and "Permission is hereby granted, free of charge" in text


def test_recalcs_licence_is_carried_for_every_file_that_cites_recalc():
    notices = (ROOT / "THIRD_PARTY_NOTICES").read_text(encoding="utf-8")
    assert "Copyright 2026 Justin Tervay" in notices
    assert "THE SOFTWARE IS PROVIDED" in notices and "Permission is hereby granted" in notices
    citing = sorted(
        path.relative_to(ROOT).as_posix()
        for folder in ("core",)
        for path in (ROOT / folder).rglob("*")
        if path.suffix in (".py", ".toml") and "tervay/recalc" in path.read_text(encoding="utf-8")
    )
    assert citing, "no file cites ReCalc: update this test"
    for name in citing:
        short = name.removeprefix("core/parts/").removeprefix("core/")
        assert name in notices or short in notices, (
            f"{name} takes from ReCalc but THIRD_PARTY_NOTICES does not name it"
        )
