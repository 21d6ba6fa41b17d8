"""Tests and docs say what they check, not which tracker issue asked for it:
no user can see the tracker."""

from __future__ import annotations

import re

from onefold_cad.layers import ROOT


def test_no_test_or_doc_cites_an_issue_number():
    found = []
    for folder in ("tests", "docs", "onefold_cad"):
        for path in sorted((ROOT / folder).rglob("*")):
            rel = path.relative_to(ROOT).as_posix()
            if path.suffix not in (".py", ".md"):
                continue
            text = path.read_text(encoding="utf-8")
            found += [
                f"{rel}:{text.count(chr(10), 0, m.start()) + 1}"
                for m in re.finditer(r"\bissue [0-9]", text)
            ]
    assert found == []
