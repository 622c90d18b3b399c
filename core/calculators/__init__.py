"""One module per calculator; each defines CALCULATOR (found by core.registry)."""
