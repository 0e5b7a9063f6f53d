"""The source digests of the stored studies: a package's files listed by name, and their
digest against hashlib over the same bytes; any edit, rename or new file changes it."""

from __future__ import annotations

import hashlib
import types

from irnuc.common.digest import named_files_digest, package_files


def _package(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "a.py").write_text("x = 1\n")
    (tmp_path / "sub" / "b.py").write_text("y = 2\n")
    (tmp_path / "preset.toml").write_text("k = 3\n")
    (tmp_path / "notes.txt").write_text("not a source\n")
    return types.SimpleNamespace(__file__=str(tmp_path / "__init__.py"))


def test_package_files_are_named_by_their_path_and_filtered(tmp_path) -> None:
    mod = _package(tmp_path)
    assert [n for n, _ in package_files(mod, "pkg", ("*.py", "*.toml"))] == [
        "pkg/a.py", "pkg/preset.toml", "pkg/sub/b.py"]
    assert [n for n, _ in package_files(mod)] == ["a.py", "sub/b.py"]
    assert [n for n, _ in package_files(mod, "s", recursive=False)] == ["s/a.py"]


def test_named_files_digest_is_sha256_of_names_and_bytes(tmp_path) -> None:
    mod = _package(tmp_path)
    files = package_files(mod, "pkg")
    h = hashlib.sha256(b"pkg/a.pyx = 1\npkg/sub/b.pyy = 2\n")
    assert named_files_digest(files) == h.hexdigest()[:16]
    before = named_files_digest(files)
    (tmp_path / "sub" / "b.py").write_text("y = 3\n")
    assert named_files_digest(package_files(mod, "pkg")) != before
    (tmp_path / "c.py").write_text("")
    assert len(package_files(mod, "pkg")) == 3
