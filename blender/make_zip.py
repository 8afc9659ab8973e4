#!/usr/bin/env python3
"""Builds the installable add-on: `python3 blender/make_zip.py OUT.zip` writes a zip holding the
folder nullpath_addon/, which Blender takes as it is: as a legacy add-on (Edit → Preferences →
Add-ons → Install) and, in Blender 4.2 and later, as an extension (its blender_manifest.toml)."""

import ast
import os
import sys
import tempfile
import tomllib
import zipfile

ADDON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "nullpath_addon")
MANIFEST = "blender_manifest.toml"
# What the zip holds: the sources and the extension's manifest.
SUFFIXES = (".py", ".toml")


def sources():
    """The add-on's files, relative to its parent, in a fixed order (the zip is reproducible)."""
    for folder, subfolders, files in os.walk(ADDON):
        subfolders[:] = sorted(d for d in subfolders if d != "__pycache__")
        for name in sorted(files):
            if name.endswith(SUFFIXES):
                path = os.path.join(folder, name)
                yield path, os.path.relpath(path, os.path.dirname(ADDON))


def bl_info_version():
    """`bl_info["version"]` of __init__.py, read without importing it (it imports bpy)."""
    with open(os.path.join(ADDON, "__init__.py"), encoding="utf-8") as file:
        module = ast.parse(file.read())
    for statement in module.body:
        if isinstance(statement, ast.Assign) and any(getattr(t, "id", None) == "bl_info" for t in statement.targets):
            return ".".join(str(n) for n in ast.literal_eval(statement.value)["version"])
    raise SystemExit("make_zip.py: nullpath_addon/__init__.py has no bl_info")


def check_versions():
    """The legacy add-on's version (bl_info) and the extension's (the manifest) are one version."""
    with open(os.path.join(ADDON, MANIFEST), "rb") as file:
        manifest = tomllib.load(file)["version"]
    legacy = bl_info_version()
    if manifest != legacy:
        sys.exit(f"make_zip.py: {MANIFEST} says version {manifest}, bl_info in __init__.py {legacy}; make them one")


def main(arguments):
    if len(arguments) != 1:
        sys.exit("usage: make_zip.py OUT.zip")
    check_versions()
    out = os.path.abspath(arguments[0])
    descriptor, temporary = tempfile.mkstemp(dir=os.path.dirname(out), prefix=".partial-", suffix=".zip")
    os.close(descriptor)
    try:
        with zipfile.ZipFile(temporary, "w", zipfile.ZIP_DEFLATED) as archive:
            for path, name in sources():
                # A fixed date: the same sources make the same zip.
                info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
                info.compress_type = zipfile.ZIP_DEFLATED
                info.external_attr = 0o644 << 16
                with open(path, "rb") as source:
                    archive.writestr(info, source.read())
        os.replace(temporary, out)
    except BaseException:
        os.unlink(temporary)
        raise


if __name__ == "__main__":
    main(sys.argv[1:])
