"""docs/robustness.md is in step with the tables."""

from __future__ import annotations

from robustness.doc import DOC, render_doc


def test_doc_lists_every_case() -> None:
    assert DOC.read_text() == render_doc(), (
        "docs/robustness.md is out of step with the tables; run "
        "`.venv/bin/python tests/robustness/doc.py`")
