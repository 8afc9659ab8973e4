#!/usr/bin/env python3
"""Builds the installable add-on: `python3 blender/make_zip.py OUT.zip` writes a zip holding the
folder nullpath_addon/ (Blender's Edit → Preferences → Add-ons → Install takes it as it is)."""

import os
import sys
import tempfile
import zipfile

ADDON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "nullpath_addon")


def sources():
    """The add-on's files, relative to its parent, in a fixed order (the zip is reproducible)."""
    for folder, subfolders, files in os.walk(ADDON):
        subfolders[:] = sorted(d for d in subfolders if d != "__pycache__")
        for name in sorted(files):
            if name.endswith(".py"):
                path = os.path.join(folder, name)
                yield path, os.path.relpath(path, os.path.dirname(ADDON))


def main(arguments):
    if len(arguments) != 1:
        sys.exit("usage: make_zip.py OUT.zip")
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
