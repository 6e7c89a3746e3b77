"""The ground-plane extent of a MESH_RESOURCE marker's mesh: read once from the file, as rviz loads it.

``mesh_resource`` is ``package://PKG/path`` (the package found as rospack finds it)
or ``file:///abs/path``.  STL (binary or ASCII) and COLLADA (.dae: every
``<float_array>`` of positions, in its unit and up axis) are read; the x and y extent of their vertices is
kept, per file, in a small cache.  A file larger than :data:`MAX_MESH_BYTES`, of
another format, or not found gives None (the marker is then drawn as a box of
its scale, and the legend says why).
"""

from __future__ import annotations

import os
import re
import stat
import struct
from functools import lru_cache
from pathlib import Path

import numpy as np

__all__ = ["MeshError", "mesh_extent", "resolve_resource", "MAX_MESH_BYTES"]

#: Largest mesh file read (a robot's meshes are a few MB).
MAX_MESH_BYTES = 64 << 20

#: Mesh files whose extent is kept.
CACHE_SIZE = 64


class MeshError(ValueError):
    """Why a mesh's extent is not known, in one line."""


def resolve_resource(url: str) -> Path:
    """The file a ``package://`` or ``file://`` resource names; MeshError when it cannot be found."""
    if url.startswith("file://"):
        return Path(url[len("file://"):])
    if url.startswith("package://"):
        package, _, rest = url[len("package://"):].partition("/")
        from rostui.core.packages import find_package

        root = find_package(package)
        if root is None:
            raise MeshError(f"package {package!r} of {url} not found")
        return root / rest
    raise MeshError(f"{url!r} is not a package:// or file:// resource")


def mesh_extent(url: str) -> tuple[float, float, float, float]:
    """``(min x, min y, max x, max y)`` of the mesh at ``url`` in its own frame, before the marker's scale."""
    return _extent_of(str(resolve_resource(url)))


def _extent_of(path: str) -> tuple[float, float, float, float]:
    """The extent of the mesh file at ``path``; a file that failed once fails again without being read."""
    extent = _extent_or_error(path)
    if isinstance(extent, MeshError):
        raise extent
    return extent


@lru_cache(maxsize=CACHE_SIZE)
def _extent_or_error(path: str) -> tuple[float, float, float, float] | MeshError:
    try:
        return _read_extent(path)
    except MeshError as exc:
        return exc


def _read_extent(path: str) -> tuple[float, float, float, float]:
    file = Path(path)
    suffix = file.suffix.lower()
    if suffix not in (".stl", ".dae"):
        raise MeshError(f"{path}: a {suffix or 'suffix-less'} mesh is not read (STL and COLLADA are)")
    try:
        fd = os.open(file, os.O_RDONLY | os.O_NONBLOCK)  # a FIFO would block an open() until a writer came
        with open(fd, "rb") as stream:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                raise MeshError(f"{path}: not a regular file")
            data = stream.read(MAX_MESH_BYTES + 1)
    except OSError as exc:
        raise MeshError(f"{path}: {exc.strerror or exc}") from None
    if len(data) > MAX_MESH_BYTES:
        raise MeshError(f"{path}: larger than {MAX_MESH_BYTES >> 20} MB")
    vertices = _stl_vertices(data, path) if suffix == ".stl" else _dae_vertices(data, path)
    finite = vertices[np.isfinite(vertices).all(axis=1)]
    if not len(finite):
        raise MeshError(f"{path}: no vertices")
    lo, hi = finite.min(axis=0), finite.max(axis=0)
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def _stl_vertices(data: bytes, path: str) -> np.ndarray:
    if len(data) >= 84:
        count = struct.unpack_from("<I", data, 80)[0]
        if 84 + 50 * count == len(data):  # binary: a normal and three vertices of float32, and two bytes, each
            records = np.frombuffer(data, dtype=np.uint8, offset=84).reshape(count, 50)
            floats = records[:, 12:48].copy().view("<f4").reshape(count * 3, 3)
            return floats[:, :2].astype(np.float64)
    text = data.decode("ascii", errors="replace")
    found = re.findall(r"vertex\s+(\S+)\s+(\S+)\s+\S+", text)
    if not found:
        raise MeshError(f"{path}: not an STL mesh")
    try:
        return np.array([(float(x), float(y)) for x, y in found], dtype=np.float64)
    except ValueError:
        raise MeshError(f"{path}: an STL vertex that is not a number") from None


def _dae_vertices(data: bytes, path: str) -> np.ndarray:
    """The ground-plane coordinates of a COLLADA file's vertex positions (each ``<vertices>``' POSITION source):
    in metres (its ``<unit meter>``), z up (a ``Y_UP`` file turned as assimp turns it for rviz: ground x, -z).
    Node transforms are not applied.  No DTD, entity or network access is taken from the file."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, huge_tree=False)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as exc:
        raise MeshError(f"{path}: not XML: {exc}") from None
    ns = {"c": root.nsmap.get(None, "")} if root.nsmap.get(None) else {}
    prefix = "c:" if ns else ""
    arrays = {}
    for source in root.iterfind(f".//{prefix}source", ns):
        floats = source.find(f"{prefix}float_array", ns)
        if floats is not None and source.get("id"):
            arrays[source.get("id")] = floats.text or ""
    blocks = []
    for node in root.iterfind(f".//{prefix}vertices/{prefix}input[@semantic='POSITION']", ns):
        text = arrays.get((node.get("source") or "").lstrip("#"))
        if text is not None:
            blocks.append(text)
    if not blocks:
        raise MeshError(f"{path}: no vertex positions in this COLLADA file")
    try:
        values = np.concatenate([np.array(block.split(), dtype=np.float64) for block in blocks])
    except ValueError:
        raise MeshError(f"{path}: a COLLADA position that is not a number") from None
    points = values[:len(values) - len(values) % 3].reshape(-1, 3)
    unit = root.find(f".//{prefix}asset/{prefix}unit", ns)
    try:
        metres = float(unit.get("meter", "1")) if unit is not None else 1.0
    except ValueError:
        metres = 1.0
    axis = root.find(f".//{prefix}asset/{prefix}up_axis", ns)
    if axis is not None and (axis.text or "").strip() == "Y_UP":
        ground = np.column_stack((points[:, 0], -points[:, 2]))
    else:
        ground = points[:, :2]
    return ground * (metres if np.isfinite(metres) and metres > 0 else 1.0)
