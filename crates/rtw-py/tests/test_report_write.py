"""The report's pages are written by the native layer (``_rtw.write_page``),
with the refusals of rtw-scan's outputs: a file rtw did not make is kept
(unless ``force``), a symlink or a directory always, and the write is atomic,
so a write that fails leaves the old page whole. Both pages (a scan's, a
design search's) go through it; Python keeps no copy of the checks."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import rtw
from rtw import _rtw

ROOT = Path(__file__).resolve().parents[3]
SCAN = ROOT / "results/paper"
DESIGN = ROOT / "results/design"
PY = ROOT / "crates/rtw-py/python/rtw"
GENERATOR = '<meta name="generator" content="rtw report">'


def _page(text: str) -> str:
    return f"<!doctype html><html><head>{GENERATOR}</head><body>{text}</body></html>"


def test_the_marker_is_the_native_layers() -> None:
    from rtw import _page as page

    assert _rtw.PAGE_GENERATOR == GENERATOR
    assert page.GENERATOR is _rtw.PAGE_GENERATOR


def test_a_file_rtw_did_not_make_is_kept_and_named_unless_force(tmp_path: Path) -> None:
    mine = tmp_path / "notes.html"
    mine.write_text("<p>my notes</p>")
    with pytest.raises(ValueError) as e:
        _rtw.write_page(mine, _page("new"), False)
    assert str(e.value) == (f"out: {mine} exists and is not an rtw report: choose another file "
                            "or pass --force (force=True)")
    assert mine.read_text() == "<p>my notes</p>"
    # The scan's page and the design page are refused the same way, before any work.
    for source in (SCAN, DESIGN):
        with pytest.raises(ValueError, match=r"out: .*notes.html exists and is not an rtw report"):
            rtw.report(source, out=mine, per_outcome=0, progress=False)
        assert mine.read_text() == "<p>my notes</p>"
    _rtw.write_page(mine, _page("new"), True)
    assert mine.read_text() == _page("new")
    assert not list(tmp_path.glob(".notes.html.*"))


def test_a_page_rtw_made_is_replaced(tmp_path: Path) -> None:
    page = tmp_path / "report.html"
    _rtw.write_page(page, _page("old"), False)
    _rtw.write_page(page, _page("new"), False)
    assert page.read_text() == _page("new")
    # A page with the marker beyond the first 4 kB is not taken for one.
    late = tmp_path / "late.html"
    late.write_text("x" * 5000 + GENERATOR)
    with pytest.raises(ValueError, match="late.html exists and is not an rtw report"):
        _rtw.write_page(late, _page("new"), False)


def test_the_page_has_the_users_permissions(tmp_path: Path) -> None:
    page = tmp_path / "report.html"
    umask = os.umask(0o022)
    try:
        _rtw.write_page(page, _page("x"), False)
    finally:
        os.umask(umask)
    assert page.stat().st_mode & 0o777 == 0o644


def test_a_symlink_or_a_directory_is_refused_even_with_force(tmp_path: Path) -> None:
    target = tmp_path / "target.html"
    target.write_text(_page("theirs"))
    link = tmp_path / "link.html"
    link.symlink_to(target)
    folder = tmp_path / "folder.html"
    folder.mkdir()
    for force in (False, True):
        with pytest.raises(ValueError) as e:
            _rtw.write_page(link, _page("new"), force)
        assert str(e.value).startswith(f"out {link}: is a symlink: rtw-scan never writes through a symlink")
        assert link.is_symlink() and target.read_text() == _page("theirs")
        with pytest.raises(ValueError) as e:
            _rtw.write_page(folder, _page("new"), force)
        assert str(e.value).startswith(f"out {folder}: is not a regular file (a directory)")
        assert folder.is_dir()
    with pytest.raises(ValueError, match="link.html: is a symlink"):
        rtw.report(SCAN, out=link, per_outcome=0, force=True, progress=False)


def test_a_missing_folder_is_named(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=f"out: the folder {tmp_path / 'no'} does not exist"):
        _rtw.write_page(tmp_path / "no" / "r.html", _page("x"), False)


def test_a_failed_write_leaves_the_old_page_whole(tmp_path: Path) -> None:
    """A write cut short (here by a file size limit, as a full disk would)
    raises naming the page, leaves the old page as it was and no temporary
    file beside it."""
    page = tmp_path / "report.html"
    old = _page("old")
    _rtw.write_page(page, old, False)
    code = (
        "import resource, signal, sys\n"
        "from rtw import _rtw\n"
        "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))\n"
        "try:\n"
        f"    _rtw.write_page({str(page)!r}, {GENERATOR!r} + 'new' * 100_000, False)\n"
        "except ValueError as e:\n"
        "    print(e)\n"
        "    sys.exit(3)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 3, r.stderr
    assert r.stdout.startswith(f"out: cannot write {page}: "), r.stdout
    assert page.read_text() == old
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.html"]


def test_python_keeps_no_copy_of_the_write() -> None:
    """The checks and the atomic write are the native layer's only."""
    for f in PY.glob("*.py"):
        text = f.read_text()
        for copy in ("tempfile", "os.replace", "mkstemp", "is_symlink"):
            assert copy not in text, f"{f.name} holds {copy}"


def _imports(module: str) -> set[str]:
    """The rtw modules `module` imports (at its top or in a function)."""
    import ast

    found = set()
    for node in ast.walk(ast.parse((PY / f"{module}.py").read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            found |= {node.module} if node.module else {a.name for a in node.names}
    return found


def test_the_two_pages_share_one_module_and_import_neither_each_other_nor_the_entry() -> None:
    scan, design = _imports("scan_page"), _imports("design_report")
    assert "_page" in scan and "_page" in design
    assert not {"report", "design_report"} & scan
    assert not {"report", "scan_page"} & design
    assert not {"report", "scan_page", "design_report"} & _imports("_page")


def test_the_python_files_stay_under_600_lines() -> None:
    for f in PY.glob("*.py"):
        assert len(f.read_text().splitlines()) <= 600, f.name
