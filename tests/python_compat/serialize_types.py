"""Fill every named message and service type with deterministic non-default values; print what genpy shows.

Run unmodified under Debian's genpy (/usr/bin/python3) and under `rostui python`; the tests compare the two
outputs.  ``serialize_types.py modules TYPES.json`` takes each class from its ``<pkg>.msg``/``<pkg>.srv``
module; ``serialize_types.py dynamic TYPES.json ROOT...`` builds genpy's classes with genpy.dynamic from the
definitions genmsg reads under the package ROOTs (for packages no Debian package ships).
TYPES.json is a list of ``[kind, "pkg/Name"]``.  Written for these tests.
"""

import importlib
import io
import itertools
import json
import sys

import genpy

COUNTER = itertools.count(1)
TEXT = ["plain", "two words", "caf\u00e9", "", "quote\"d", "new\nline"]


def module_class(type_name, kind):
    package, name = type_name.split("/")
    return getattr(importlib.import_module(package + "." + kind), name)


def scalar(base, get_class):
    n = next(COUNTER)
    if base == "bool":
        return n % 2 == 1
    if base in ("int8", "byte"):
        return n % 200 - 100
    if base in ("uint8", "char"):
        return n * 7 % 256
    if base == "int16":
        return n * 37 % 60000 - 30000
    if base == "uint16":
        return n * 37 % 65000
    if base == "int32":
        return -n * 100003
    if base == "uint32":
        return n * 100003
    if base == "int64":
        return -(n * 10 ** 12 + 7)
    if base == "uint64":
        return n * 10 ** 12 + 7
    if base == "float32":
        return n / 8.0 + 0.25
    if base == "float64":
        return n / 7.0
    if base == "string":
        return TEXT[n % len(TEXT)] + str(n)
    if base == "time":
        return genpy.Time(n, n * 1000003 % 1000000000)
    if base == "duration":
        return genpy.Duration(-n, n * 999)
    return fill(get_class(base), get_class)


def value(slot_type, get_class):
    base, bracket, rest = slot_type.partition("[")
    if not bracket:
        return scalar(base, get_class)
    size = int(rest[:-1]) if rest[:-1] else next(COUNTER) % 3 + 1
    items = [scalar(base, get_class) for _ in range(size)]
    return bytes(items) if base in ("uint8", "char") else items


def fill(cls, get_class):
    msg = cls()
    for name, slot_type in zip(cls.__slots__, cls._slot_types):
        setattr(msg, name, value(slot_type, get_class))
    return msg


def show(cls, get_class, with_text):
    global COUNTER
    COUNTER = itertools.count(1)
    msg = fill(cls, get_class)
    buff = io.BytesIO()
    msg.serialize(buff)
    data = buff.getvalue()
    back = cls().deserialize(data)
    out = {"type": cls._type, "md5": cls._md5sum, "slots": list(cls.__slots__), "slot_types": list(cls._slot_types),
           "has_header": cls._has_header, "hex": data.hex(), "str": str(msg), "back_equal": back == msg,
           "back_str": str(back), "empty_str": str(cls())}
    if with_text:
        out["full_text"] = cls._full_text
    return out


def dynamic_classes(types, roots):
    import genmsg.gentools as gt
    import genmsg.msg_loader as ml
    import genpy.dynamic

    search = {}
    for root in roots:
        import os
        for pkg in sorted(os.listdir(root)):
            dirs = [os.path.join(root, pkg, k) for k in ("msg", "srv") if os.path.isdir(os.path.join(root, pkg, k))]
            if dirs and pkg not in search:
                search[pkg] = dirs
    classes = {}

    def build(type_name, ctx, spec):
        path = list(sys.path)
        classes[type_name] = genpy.dynamic.generate_dynamic(type_name, gt.compute_full_text(ctx, spec))
        # generate_dynamic leaves its module's folder on sys.path: a thousand of them made every later import
        # search a thousand folders (6 of its 20 CPU seconds here)
        sys.path[:] = path

    for kind, type_name in types:
        ctx = ml.MsgContext.create_default()
        try:
            if kind == "msg":
                spec = ml.load_msg_by_type(ctx, type_name, search)
                ml.load_depends(ctx, spec, search)
                build(type_name, ctx, spec)
            else:
                spec = ml.load_srv_by_type(ctx, type_name, search)
                ml.load_depends(ctx, spec, search)
                build(type_name + "Request", ctx, spec.request)
                build(type_name + "Response", ctx, spec.response)
        except Exception:
            continue
    return classes


def main():
    how, types_file = sys.argv[1], sys.argv[2]
    with open(types_file) as f:
        types = [tuple(t) for t in json.load(f)]
    if how == "modules":
        def resolver(top):
            return lambda type_name: module_class(type_name, "msg")

        def srv_halves(type_name):
            srv = module_class(type_name, "srv")
            return srv._request_class, srv._response_class
    else:
        classes = dynamic_classes(types, sys.argv[3:])

        def resolver(top):  # genpy.dynamic builds a new set of classes for every type
            return lambda type_name: classes[top][type_name]

        def srv_halves(type_name):
            return (resolver(type_name + "Request")(type_name + "Request"),
                    resolver(type_name + "Response")(type_name + "Response"))
    out = {}
    for kind, type_name in types:
        try:
            if kind == "msg":
                out[type_name] = show(resolver(type_name)(type_name), resolver(type_name), how == "modules")
            else:
                request, response = srv_halves(type_name)
                out[type_name] = {"request": show(request, resolver(type_name + "Request"), how == "modules"),
                                  "response": show(response, resolver(type_name + "Response"), how == "modules")}
                if how == "modules":
                    srv = module_class(type_name, "srv")
                    out[type_name]["md5"] = srv._md5sum
                    out[type_name]["type"] = srv._type
        except Exception as exc:
            out[type_name] = {"error": type(exc).__name__}
    json.dump(out, sys.stdout, indent=1, sort_keys=True)


main()
