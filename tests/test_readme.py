"""The README's Python snippet prints what the README says it prints."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parent.parent / "README.md"


@pytest.mark.skipif(not README.is_file(), reason="README not shipped in this install")
def test_readme_snippet_output():
    text = README.read_text()
    code, expected = re.search(
        r"```python\n(.*?)```\s*\nprints\s*\n\s*```\n(.*?)```", text, re.S
    ).groups()
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README.md", "exec"), {})
    assert out.getvalue() == expected


@pytest.mark.skipif(not README.is_file(), reason="README not shipped in this install")
def test_readme_opens_with_the_two_setup_commands():
    block = re.search(r"```sh\n(.*?)```", README.read_text(), re.S).group(1).splitlines()
    assert len(block) == 2
    assert block[0].startswith("python3 -m venv .venv && ") and "hexaleg report" in block[0]
    assert block[1].startswith("python3 -m venv .venv && ") and block[1].endswith("pytest")
