#!/usr/bin/env python3
"""Makes fuzz_snapshot's two-car seed from drive's one-car seed (fuzz/CMakeLists.txt).

The car is copied 1.5 m to its side and the two listed as touching, so that the fuzzer's
inputs reach a touching list that restores (io/snapshot_file.hpp has the layout).
Usage: touching_seed.py flat_ground.snap.seed two_touching.snap.seed
"""
import struct
import sys

HEADER = 32
SETTINGS = 88  # f64, 2 u32, f64[3], f64, 2 u32, 4 f64
ELLIPSOID = 8 * 8 + 2 * 4


def fnv1a(data):
    value = 0xCBF29CE484222325
    for byte in data:
        value = ((value ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return value


def main(source, target):
    data = open(source, "rb").read()
    payload = data[HEADER:]
    colliders = struct.unpack_from("<I", payload, 0)[0]
    cars_at = 4 + 24 * colliders + SETTINGS + 8
    assert struct.unpack_from("<I", payload, cars_at)[0] == 1, "drive saves one car"
    car_at = cars_at + 4
    ellipsoids = struct.unpack_from("<I", payload, car_at + 8 + 13 * 8 + 3 * 8)[0]
    vehicle_at = car_at + 8 + 13 * 8 + 3 * 8 + 4 + ellipsoids * ELLIPSOID + 8
    assert struct.unpack_from("<I", payload, vehicle_at)[0] == 0, "the default car is arcade"
    car = payload[car_at:vehicle_at + 4]
    touching_at = vehicle_at + 4
    assert struct.unpack_from("<I", payload, touching_at)[0] == 0
    x = struct.unpack_from("<d", car, 8)[0]
    beside = car[:8] + struct.pack("<d", x + 1.5) + car[16:]
    new_payload = (payload[:cars_at] + struct.pack("<I", 2) + car + beside +
                   struct.pack("<IIId", 1, 0, 1, 0.01) + payload[touching_at + 4:])
    header = data[:16] + struct.pack("<QQ", len(new_payload), fnv1a(new_payload))
    open(target, "wb").write(header + new_payload)


if __name__ == "__main__":
    main(*sys.argv[1:])
