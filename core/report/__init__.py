"""The design report (issue 45): a preset or a workbook as pages a team prints, submits and reviews.

`document` builds the report's content as plain data (no formatting of its own: every value is the
text the CLI's `solve`, `check` and `match` print, from the same functions); `html` and `markdown`
write it; `charts` draws its charts with matplotlib, the only module that imports it (the app and
the CLI's other commands never pay for it); `pdf` prints the HTML with a headless Chromium.
"""

from .document import Report, build, from_preset, from_workbook

__all__ = ["Report", "build", "from_preset", "from_workbook"]
