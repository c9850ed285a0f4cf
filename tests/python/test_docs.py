"""The Python blocks of the documentation run as they stand (docs/python.md, README.md)."""
import os
import re

import pytest


def python_blocks(text):
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


@pytest.mark.parametrize("page", ["README.md", "docs/python.md"])
def test_the_python_blocks_of_the_page_run_in_order_from_the_repository_root(page, source_dir, monkeypatch):
    blocks = python_blocks((source_dir / page).read_text())
    assert blocks, f"{page} has no Python block"
    monkeypatch.chdir(source_dir)
    namespace: dict[str, object] = {}
    for number, block in enumerate(blocks, start=1):
        try:
            exec(compile(block, f"{page}, Python block {number}", "exec"), namespace)
        except Exception as error:  # noqa: BLE001  the block and the error are the report
            pytest.fail(f"{page}, Python block {number} raised {error!r}:\n{block}")
    assert "mm" in namespace
