"""The memory estimates (``memory.py``) and the check that uses them."""

from __future__ import annotations

from pathlib import Path

import pytest

from robustness.memory import MEASURED


@pytest.mark.parametrize("what", [m[0] for m in MEASURED])
def test_memory_estimate_covers_measured_peak(what: str) -> None:
    measured, estimate = next((m[1], m[2]) for m in MEASURED if m[0] == what)
    assert estimate() >= measured * 2**20


def test_memory_check_names_estimate_and_available(monkeypatch: pytest.MonkeyPatch) -> None:
    from irnuc.common import memory

    monkeypatch.delenv("IRNUC_NO_MEMORY_CHECK", raising=False)
    monkeypatch.setattr(memory, "available_bytes", lambda: 1000)
    with pytest.raises(memory.ResourceError, match=r"^--x 3 needs an estimated 2.0 KiB of "
                       r"memory but only 1000 B is available; use less$"):
        memory.check_memory(2000, "--x 3", "use less")
    memory.check_memory(800, "--x 1")  # 80 % of what is available may be planned
    monkeypatch.setenv("IRNUC_NO_MEMORY_CHECK", "1")
    memory.check_memory(10**20, "--x 9")  # the user's choice
    monkeypatch.delenv("IRNUC_NO_MEMORY_CHECK")
    monkeypatch.setattr(memory, "available_bytes", lambda: None)
    memory.check_memory(10**20, "--x 9")  # nothing to compare with: no refusal


def test_meminfo_is_read(tmp_path: Path) -> None:
    from irnuc.common import memory

    f = tmp_path / "meminfo"
    f.write_text("MemTotal:       32000000 kB\nMemFree:  100 kB\nMemAvailable:   2048 kB\n")
    assert memory._meminfo_available(str(f)) == 2048 * 1024
    assert memory._meminfo_available(str(tmp_path / "none")) is None
    assert memory.available_bytes() is None or memory.available_bytes() > 0
