#!/usr/bin/env python3
"""`trackphys drive --resume` of a snapshot whose drive session was edited and the file
re-sealed (its checksum, FNV-1a 64, guards against damage, not against an edit): each edit
must be refused with exit status 1 and a message naming the file and what is wrong, not
resumed into a report of impossible figures (laps -2147483648 after a wrapped count, a drive
of nothing past its end, a negative lap time).

Usage: edited_snapshot_test.py TRACKPHYS_COMMAND WORK_DIR
"""

import json
import shutil
import struct
import subprocess
import sys
from pathlib import Path

HEADER_BYTES = 32  # magic 8, version 4, reserved 4, payload length 8, checksum 8


def fnv1a(data):
    value = 0xCBF29CE484222325
    for byte in data:
        value = ((value ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return value


def split(snapshot):
    """The payload before the user data, and the user data as JSON (the payload's last field,
    after its u64 length)."""
    payload = snapshot[HEADER_BYTES:]
    start = payload.rfind(b'{"autopilot"')
    assert start >= 8, "no drive session in the snapshot"
    (length,) = struct.unpack_from("<Q", payload, start - 8)
    assert length == len(payload) - start, "the user data is not the payload's end"
    return snapshot[:8 + 8], payload[:start - 8], json.loads(payload[start:])


def sealed(head, before, session):
    user = json.dumps(session).encode()
    payload = before + struct.pack("<Q", len(user)) + user
    return head + struct.pack("<QQ", len(payload), fnv1a(payload)) + payload


def main():
    command, work = sys.argv[1], Path(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    original = work / "drive.snap"
    subprocess.run([command, "drive", "--seconds", "1", "--save-at", "0.5", str(original)],
                   check=True, stdout=subprocess.DEVNULL)
    head, before, session = split(original.read_bytes())

    def edited(change):
        copy = json.loads(json.dumps(session))
        change(copy)
        return copy

    def set_autopilot(key, value):
        return lambda s: s["autopilot"].__setitem__(key, value)

    def set_field(key, value):
        return lambda s: s.__setitem__(key, value)

    cases = {
        "laps_at_int_max": (set_autopilot("laps", 2147483647), "laps is not a whole number"),
        "laps_wrapping_to_5": (set_autopilot("laps", 2**32 + 5), "laps is not a whole number"),
        "laps_a_fraction": (set_autopilot("laps", 1.5), "laps is not a whole number"),
        "laps_without_lap_times": (set_autopilot("laps", 5),
                                   "autopilot.laps is more than the lap times"),
        "negative_distance": (set_field("distance_m", -1e308), "distance_m is not finite"),
        "negative_lap_time": (lambda s: (s.__setitem__("lap_times_s", [-1.0]),
                                         s["autopilot"].__setitem__("laps", 1)),
                              "a lap time is not finite and > 0"),
    }
    # The unedited session, re-sealed, still resumes: the edits alone are refused.
    control = work / "control.snap"
    control.write_bytes(sealed(head, before, session))
    subprocess.run([command, "drive", "--seconds", "1", "--resume", str(control)],
                   check=True, stdout=subprocess.DEVNULL)
    failures = []
    for name, (change, reason) in cases.items():
        path = work / f"{name}.snap"
        path.write_bytes(sealed(head, before, edited(change)))
        run = subprocess.run([command, "drive", "--seconds", "1", "--resume", str(path)],
                             capture_output=True, text=True)
        named = f"--resume '{path}': the snapshot's drive session is not valid: "
        if run.returncode != 1 or named not in run.stderr or reason not in run.stderr:
            failures.append(f"{name}: exit {run.returncode}, stderr {run.stderr.strip()!r}, "
                            f"expected {named}...{reason}")
    for failure in failures:
        print(failure)
    print(f"{len(cases) - len(failures)} of {len(cases)} edited sessions refused")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
