"""Built-in presets, presets/<calculator>/<name>.toml (a package so `pip install .` ships them)."""
