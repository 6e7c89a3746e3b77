"""Textual SVG snapshots kept in ``snapshots/<test module>/`` at the repository root.

pytest-textual-snapshot's ``snap_compare`` stores SVGs through syrupy beside
the test file by default; a test module that imports :func:`snapshot` from
here stores them under the repository's ``snapshots/`` instead.  Update with
``pytest tests/<module>.py --snapshot-update``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional, Type

import pytest
from pytest_textual_snapshot import SVGImageExtension
from syrupy.assertion import SnapshotAssertion
from syrupy.extensions.base import AbstractSyrupyExtension
from syrupy.location import PyTestLocation

from conftest import REPO

SNAPSHOT_ROOT = REPO / "snapshots"


class RepoSVGExtension(SVGImageExtension):
    """SVG snapshots in ``snapshots/<test module name>/``."""

    @classmethod
    def dirname(cls, *, test_location: PyTestLocation) -> str:
        """The module's folder below ``snapshots/``."""
        return str(SNAPSHOT_ROOT / Path(test_location.filepath).stem)


class RepoSnapshotAssertion(SnapshotAssertion):
    """A syrupy assertion that swaps the plugin's SVG extension for :class:`RepoSVGExtension`."""

    def use_extension(self, extension_class: Optional[Type[AbstractSyrupyExtension]] = None) -> Any:
        """Use ``extension_class``, storing SVGs in the repository's snapshots folder."""
        if extension_class is SVGImageExtension:
            extension_class = RepoSVGExtension
        return super().use_extension(extension_class)


@pytest.fixture
def snapshot(snapshot: SnapshotAssertion) -> SnapshotAssertion:
    """syrupy's ``snapshot`` fixture, redirected to ``snapshots/`` for ``snap_compare``."""
    return RepoSnapshotAssertion(
        update_snapshots=snapshot.update_snapshots,
        extension_class=snapshot.extension_class,
        test_location=snapshot.test_location,
        session=snapshot.session,
    )


@pytest.fixture(autouse=True)
def truecolor(monkeypatch: pytest.MonkeyPatch) -> None:
    """The same colour system on every machine (autouse in each module that imports it)."""
    monkeypatch.setenv("COLORTERM", "truecolor")
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)
