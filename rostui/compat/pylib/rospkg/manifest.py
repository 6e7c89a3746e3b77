"""rospkg.manifest: a package's manifest (``package.xml``, or rosbuild's ``manifest.xml``) as rospkg reads it."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ElementTree
from pathlib import Path
from typing import Any

from .common import MANIFEST_FILE, PACKAGE_FILE

__all__ = ["Depend", "Export", "InvalidManifest", "Manifest", "parse_manifest_file"]

#: package.xml's dependency tags counted, as the rospack command counts them: the run-time ones
#: (``<depend>`` includes ``<exec_depend>``; format 1's is ``<run_depend>``).
DEPEND_TAGS = ("exec_depend", "run_depend", "depend")


class InvalidManifest(Exception):
    """A manifest file that cannot be read."""


class Depend:
    """A dependency: a package's name and its type ("package")."""

    __slots__ = ("name", "type")

    def __init__(self, name: str, type_: str) -> None:
        if not name:
            raise ValueError(f"bad '{type_}' attribute")
        if not type_:
            raise ValueError("type_ must be specified")
        self.name, self.type = name, type_

    def __str__(self) -> str:
        return self.name

    __repr__ = __str__

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Depend) and (self.name, self.type) == (other.name, other.type)

    def __hash__(self) -> int:
        return hash((self.name, self.type))


class Export:
    """One element of ``<export>``: its tag, attributes and text."""

    def __init__(self, tag: str, attrs: dict[str, str], str: str) -> None:  # noqa: A002 (rospkg's name)
        self.tag, self.attrs, self.str = tag, attrs, str

    def get(self, attr: str) -> str | None:
        """The attribute's value, or None."""
        return self.attrs.get(attr)


class Manifest:
    """A package's manifest: description, author, licence, url, version, dependencies and exports."""

    def __init__(self, type_: str = "package", filename: str | None = None, is_catkin: bool = False) -> None:
        self.description = self.brief = self.author = self.license = self.license_url = ""
        self.url = self.status = self.version = self.notes = ""
        self.licenses: list[str] = []
        self.depends: list[Depend] = []
        self.rosdeps: list[Any] = []
        self.exports: list[Export] = []
        self.platforms: list[Any] = []
        self.unknown_tags: list[Any] = []
        self.is_catkin = is_catkin
        self.type = type_
        self.filename = filename

    def get_export(self, tag: str, attr: str, convert: bool = True) -> list[str]:
        """The values of attribute *attr* of the exports named *tag*; ``${prefix}`` becomes the package's folder."""
        values = [v for e in self.exports if e.tag == tag for v in [e.get(attr)] if v is not None]
        if convert:
            if not self.filename:
                raise ValueError("cannot convert export values when filename for Manifest is not set")
            prefix = os.path.dirname(self.filename)
            values = [v.replace("${prefix}", prefix) for v in values]
        return values


def _text(root: ElementTree.Element, tag: str) -> str:
    return (root.findtext(tag) or "").strip()


def _exports(root: ElementTree.Element) -> list[Export]:
    return [Export(child.tag, dict(child.attrib), (child.text or "").strip())
            for export in root.findall("export") for child in export if isinstance(child.tag, str)]


def parse_manifest_file(dirpath: str, manifest_name: str = MANIFEST_FILE,
                        known: frozenset[str] | None = None) -> Manifest:
    """The manifest of the package in *dirpath*: its ``manifest.xml`` (rosbuild) or else its ``package.xml``.

    A package.xml's dependencies are its run-time ones that are ROS packages (*known*), as the rospack command
    lists them."""
    folder = Path(dirpath)
    filename = folder / manifest_name
    source = filename if filename.is_file() else folder / PACKAGE_FILE
    if not source.is_file():
        raise OSError(f"Invalid/non-existent manifest file: {filename}")
    try:
        root = ElementTree.parse(source).getroot()
    except (ElementTree.ParseError, OSError) as exc:
        raise InvalidManifest(f"[{source}] invalid XML: {exc}") from None
    manifest = Manifest(filename=str(filename), is_catkin=source.name == PACKAGE_FILE)
    manifest.description = _text(root, "description")
    manifest.version = _text(root, "version")
    manifest.exports = _exports(root)
    licenses = [(e.text or "").strip() for e in root.findall("license")]
    manifest.licenses, manifest.license = licenses, ", ".join(licenses)
    urls = [(e.text or "").strip() for e in root.findall("url")]
    manifest.url = urls[0] if urls else ""
    if manifest.is_catkin:
        maintainers = [f"Maintainer: {(m.text or '').strip()}" for m in root.findall("maintainer")]
        manifest.author = ", ".join(maintainers + [(a.text or "").strip() for a in root.findall("author")])
        names = {(e.text or "").strip() for tag in DEPEND_TAGS for e in root.findall(tag)}
        manifest.depends = [Depend(name, "package") for name in sorted(names) if name and (known is None or name in known)]
    else:
        manifest.author = _text(root, "author")
        manifest.depends = [Depend(e.get("package", ""), "package") for e in root.findall("depend") if e.get("package")]
        manifest.is_catkin = root.find("catkin") is not None
    return manifest
