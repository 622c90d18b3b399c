"""Gearhead's pure computational core: SI floats in, SI floats out.

Never imports textual, rich or tui (tests/test_architecture.py enforces it).
"""
