"""Example workbooks shipped with Gearhead (README "Workbooks"): `gearhead check` runs them as they are."""
