"""Runs the `nullpath` program: finding it, following its progress, stopping it when asked."""

import os
import re
import shutil
import subprocess
import threading
import time

import bpy

ADDON_NAME = __package__
# `nullpath render --progress-lines` writes `progress DONE TOTAL` lines on standard error.
PROGRESS = re.compile(r"^progress (\d+) (\d+)$")
POLL_SECONDS = 0.1


class RunError(Exception):
    """The program could not be found, failed, or was stopped."""


def binary():
    """The nullpath program: the add-on's preference, else $NULLPATH_BIN, else `nullpath` on PATH."""
    addon = bpy.context.preferences.addons.get(ADDON_NAME)
    chosen = bpy.path.abspath(addon.preferences.binary) if addon and addon.preferences.binary else ""
    for candidate, source in ((chosen, "the add-on's preferences"), (os.environ.get("NULLPATH_BIN", ""), "$NULLPATH_BIN")):
        if candidate:
            if not (os.path.isfile(candidate) and os.access(candidate, os.X_OK)):
                raise RunError(f"nullpath program '{candidate}' (from {source}) is not an executable file")
            return candidate
    found = shutil.which("nullpath")
    if found is None:
        raise RunError("cannot find the nullpath program: set its path in the add-on's preferences or $NULLPATH_BIN, or put it on PATH")
    return found


def run(arguments, progress, cancelled):
    """Runs nullpath with `arguments`, reporting `progress(fraction)` from its progress lines and
    terminating it (SIGTERM: it stops within a sample) when `cancelled()`. Returns its standard
    error; raises RunError if it fails or is cancelled."""
    process = subprocess.Popen(
        [binary(), *arguments], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
        text=True, errors="replace",
    )
    lines = []
    reader = threading.Thread(target=collect, args=(process.stderr, lines), daemon=True)
    reader.start()
    seen = 0
    while process.poll() is None:
        if cancelled():
            process.terminate()
            process.wait()
            reader.join()
            raise RunError("cancelled")
        seen = report(lines, seen, progress)
        time.sleep(POLL_SECONDS)
    reader.join()
    report(lines, seen, progress)
    messages = "".join(line for line in lines if not PROGRESS.match(line.strip()))
    if process.returncode != 0:
        raise RunError(messages.strip() or f"nullpath exited with status {process.returncode}")
    return messages


def collect(stream, lines):
    """Appends each line of `stream` to `lines` as it comes (a thread of its own, so that a full
    pipe never blocks the program)."""
    for line in stream:
        lines.append(line)


def report(lines, seen, progress):
    """Reports the latest progress line after the first `seen` lines; how many lines it has seen."""
    count = len(lines)
    for line in reversed(lines[seen:count]):
        match = PROGRESS.match(line.strip())
        if match:
            done, total = int(match.group(1)), int(match.group(2))
            progress(done / total if total else 0.0)
            break
    return count
