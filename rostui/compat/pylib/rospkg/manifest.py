"""rospkg.manifest: a package's or stack's manifest as rospkg reads it: rosbuild's ``manifest.xml`` and
``stack.xml`` (``parse_manifest``), or a catkin ``package.xml`` standing in for a missing ``manifest.xml``."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ElementTree
from collections.abc import Collection
from pathlib import Path
from typing import Any

from .common import MANIFEST_FILE, PACKAGE_FILE, STACK_FILE

__all__ = [
    "Depend", "Export", "InvalidManifest", "MANIFEST_FILE", "Manifest", "PACKAGE_FILE", "Platform", "RosDep",
    "STACK_FILE", "parse_manifest", "parse_manifest_file",
]

#: The elements a rosbuild manifest may hold; others are kept in ``Manifest.unknown_tags``.
KNOWN_TAGS = frozenset({
    "license", "author", "logo", "url", "brief", "description", "status", "notes", "depend", "rosdep", "export",
    "review", "versioncontrol", "platform", "version", "rosbuild2", "catkin",
})

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


class RosDep:
    """A system dependency (a rosdep key) named in a rosbuild manifest."""

    __slots__ = ("name",)

    def __init__(self, name: str) -> None:
        self.name = name


class Platform:
    """A platform a rosbuild package supports: operating system, version and notes."""

    __slots__ = ("os", "version", "notes")

    def __init__(self, os_: str, version: str, notes: str | None = None) -> None:
        if not os_:
            raise ValueError("bad 'os' attribute")
        if not version:
            raise ValueError("bad 'version' attribute")
        self.os, self.version, self.notes = os_, version, notes

    def __str__(self) -> str:
        return f"{self.os} {self.version}"

    __repr__ = __str__

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Platform) and (self.os, self.version, self.notes) == (other.os, other.version,
                                                                                        other.notes)

    def __hash__(self) -> int:
        return hash((self.os, self.version, self.notes))


class Export:
    """One element of ``<export>``: its tag, attributes and text."""

    def __init__(self, tag: str, attrs: dict[str, str], str: str) -> None:  # noqa: A002 (rospkg's name)
        self.tag, self.attrs, self.str = tag, attrs, str

    def get(self, attr: str) -> str | None:
        """The attribute's value, or None."""
        return self.attrs.get(attr)


class Manifest:
    """A package's or stack's (*type_*) manifest: description, author, licence, url, version, dependencies,
    rosdeps, platforms and exports."""

    def __init__(self, type_: str = "package", filename: str | None = None, is_catkin: bool = False) -> None:
        self.description = self.brief = self.author = self.license = self.license_url = ""
        self.url = self.status = self.version = self.notes = ""
        self.licenses: list[str] = []
        self.depends: list[Depend] = []
        self.rosdeps: list[RosDep] = []
        self.exports: list[Export] = []
        self.platforms: list[Platform] = []
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


def _children(node: ElementTree.Element, tag: str) -> list[ElementTree.Element]:
    return [child for child in node if child.tag == tag]


def _inner_text(node: ElementTree.Element, xhtml: bool) -> str:
    """An element's text; with *xhtml*, its child elements too, as XML (a description may hold XHTML)."""
    if not xhtml:
        return "".join([node.text or ""] + [child.tail or "" for child in node])
    parts = [node.text or ""]
    for child in node:
        parts.append(ElementTree.tostring(child, encoding="unicode"))  # the child's tail is part of its XML here
    return "".join(parts)


def _single(node: ElementTree.Element, tag: str, filename: str, merge: bool = False) -> str:
    """The text of the one ``<tag>`` (several joined with ", " when *merge*); "" when there is none."""
    found = _children(node, tag)
    if len(found) > 1 and not merge:
        raise InvalidManifest(f"Invalid manifest file [{filename}]: must have a single '{tag}' element")
    xhtml = tag == "description"
    return ", ".join(_inner_text(e, xhtml) if xhtml else _inner_text(e, xhtml).strip() for e in found)


def _required_attribute(element: ElementTree.Element, attribute: str, filename: str) -> str:
    value = element.get(attribute)
    if value is None:
        raise InvalidManifest(f"Invalid manifest file [{filename}]: <{element.tag}> is missing its '{attribute}' attribute")
    return value


def parse_manifest(manifest_name: str, string: str | bytes, filename: str = "string") -> Manifest:
    """A rosbuild ``manifest.xml`` (*manifest_name* MANIFEST_FILE) or ``stack.xml`` (STACK_FILE) from its text.

    Raises InvalidManifest, naming *filename*, for bad XML, a wrong root element, a repeated single-valued
    element, or a stack manifest with exports or rosdeps."""
    type_ = "stack" if manifest_name == STACK_FILE else "package"
    try:
        root = ElementTree.fromstring(string)
    except ElementTree.ParseError as exc:
        raise InvalidManifest(f"[{filename}] invalid XML: {exc}") from None
    if root.tag != type_:
        raise InvalidManifest(f"manifest [{filename}] must have a single '{type_}' element")
    manifest = Manifest(type_, filename)
    manifest.description = _single(root, "description", filename)
    descriptions = _children(root, "description")
    manifest.brief = descriptions[0].get("brief", "") if descriptions else ""
    manifest.depends = [Depend(_required_attribute(e, type_, filename), type_)
                        for e in _children(root, "depend") if "thirdparty" not in e.attrib]
    manifest.rosdeps = [RosDep(_required_attribute(e, "name", filename)) for e in _children(root, "rosdep")]
    manifest.platforms = [Platform(_required_attribute(e, "os", filename), _required_attribute(e, "version", filename),
                                   e.get("notes", "")) for e in _children(root, "platform")]
    manifest.exports = _exports(root)
    manifest.license = _single(root, "license", filename)
    licenses = _children(root, "license")
    manifest.license_url = licenses[0].get("url", "") if licenses else ""
    reviews = _children(root, "review")
    manifest.status = reviews[0].get("status", "") if reviews else "unreviewed"
    manifest.notes = reviews[0].get("notes", "") if reviews else ""
    manifest.author = _single(root, "author", filename, merge=True)
    manifest.url = _single(root, "url", filename)
    manifest.version = _single(root, "version", filename)
    if type_ == "stack" and manifest.exports:
        raise InvalidManifest("stack manifests are not allowed to have exports")
    if type_ == "stack" and manifest.rosdeps:
        raise InvalidManifest("stack manifests are not allowed to have rosdeps")
    manifest.is_catkin = bool(_children(root, "catkin") or _children(root, "name"))
    manifest.unknown_tags = [e for e in root if isinstance(e.tag, str) and e.tag not in KNOWN_TAGS]
    return manifest


def _exports(root: ElementTree.Element) -> list[Export]:
    return [Export(child.tag, dict(child.attrib), (child.text or "").strip())
            for export in _children(root, "export") for child in export if isinstance(child.tag, str)]


def _parse_package_xml(source: Path, filename: Path, known: Collection[str] | None) -> Manifest:
    """A catkin ``package.xml`` read as rospkg reads it for a manifest.xml that is not there."""
    try:
        root = ElementTree.parse(source).getroot()
    except (ElementTree.ParseError, OSError) as exc:
        raise InvalidManifest(f"[{source}] invalid XML: {exc}") from None
    manifest = Manifest(filename=str(filename), is_catkin=True)
    manifest.description = (root.findtext("description") or "").strip()
    manifest.version = (root.findtext("version") or "").strip()
    manifest.exports = _exports(root)
    manifest.licenses = [(e.text or "").strip() for e in root.findall("license")]
    manifest.license = ", ".join(manifest.licenses)
    urls = [(e.text or "").strip() for e in root.findall("url")]
    manifest.url = urls[0] if urls else ""
    maintainers = [f"Maintainer: {(m.text or '').strip()}" for m in root.findall("maintainer")]
    manifest.author = ", ".join(maintainers + [(a.text or "").strip() for a in root.findall("author")])
    names = {(e.text or "").strip() for tag in DEPEND_TAGS for e in root.findall(tag)}
    manifest.depends = [Depend(name, "package") for name in sorted(names) if name and (known is None or name in known)]
    return manifest


def parse_manifest_file(dirpath: str, manifest_name: str = MANIFEST_FILE,
                        rospack: Any = None) -> Manifest:
    """The manifest of the package (or stack) in *dirpath*: its *manifest_name* file, or else its ``package.xml``.

    A package.xml's dependencies are its run-time ones that are ROS packages (those *rospack*, a RosPack,
    lists; all of them without one), as the rospack command lists them."""
    folder = Path(dirpath)
    filename = folder / manifest_name
    if filename.is_file():
        return parse_manifest(manifest_name, filename.read_bytes(), str(filename))
    source = folder / PACKAGE_FILE
    if not source.is_file():
        raise OSError(f"Invalid/non-existent manifest file: {filename}")
    return _parse_package_xml(source, filename, None if rospack is None else rospack.list())
