#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_arcos_decoder (tests/fuzz/corpus/arcos/) from the
known-answer vectors of docs/arcos-protocol.md. Run it from anywhere; it rewrites
the files in place. Each file: one control byte (chunking/timing seed, bit 7 =
count limit 200), then the byte stream."""

import pathlib
import struct

OUT = pathlib.Path(__file__).resolve().parent / "corpus" / "arcos"


def checksum(body: bytes) -> int:
    total = 0
    for i in range(0, len(body) - 1, 2):
        total = (total + (body[i] << 8) + body[i + 1]) & 0xFFFF
    if len(body) % 2:
        total ^= body[-1]
    return total


def frame(packet_id: int, payload: bytes = b"") -> bytes:
    body = bytes([packet_id]) + payload
    return bytes([0xFA, 0xFB, len(body) + 2]) + body + struct.pack(">H", checksum(body))


def int_arg(value: int) -> bytes:
    return bytes([0x3B if value >= 0 else 0x1B]) + struct.pack("<H", min(abs(value), 0xFFFF))


# The doc's vectors, byte for byte (checked against frame() below).
GOLDEN = {
    "sync0": bytes.fromhex("FAFB03000000"),
    "sync1": bytes.fromhex("FAFB03010001"),
    "sync2": bytes.fromhex("FAFB03020002"),
    "vel300": bytes.fromhex("FAFB060B3B2C01373C"),
    "rvel-20": bytes.fromhex("FAFB06151B1400291B"),
    "open1": bytes.fromhex("FAFB06013B0100023B"),
    "config1": bytes.fromhex("FAFB06123B0100133B"),
    "vel2": bytes.fromhex("FAFB06201BF6091624"),
    "sync2_reply": bytes.fromhex("FAFB1802") + b"AMRISim\0Pioneer\0p3at\0" + bytes.fromhex("E7BA"),
}
assert GOLDEN["vel300"] == frame(0x0B, int_arg(300))
assert GOLDEN["rvel-20"] == frame(0x15, int_arg(-20))
assert GOLDEN["vel2"] == frame(0x20, int_arg(-2550))
assert GOLDEN["sync2_reply"] == frame(0x02, b"AMRISim\0Pioneer\0p3at\0")

# A SIP (§5) with two sonar readings and every optional group.
SIP = frame(0x33, struct.pack("<HHhhhBHhHBB", 0x1234, 0x0456, 1024, -300, 300, 128, 0x0101, 0, 1, 45, 2)
            + struct.pack("<BHBH", 0, 5000, 15, 250)
            + bytes([0, 0, 0, 0, 0]) + struct.pack("<HBhHhbBII", 131, 2, -455, 0x10, 0, -127, 0, 123456, 0))

# A short config reply (§6), cut after the current maxima.
CONFIG = frame(0x20, b"Pioneer\0p3at\0SIM\0" + b"\0" + struct.pack("<5H", 300, 3000, 300, 1000, 1000)
               + b"sim\0" + bytes([100, 0, 0]) + struct.pack("<HHB", 0, 1, 1)
               + struct.pack("<HHHB", 110, 0, 2000, 0) + struct.pack("<6H", 0, 0, 0, 0, 150, 3000))

SEEDS = {
    "handshake": bytes([0x00]) + GOLDEN["sync0"] + GOLDEN["sync1"] + GOLDEN["sync2"] + GOLDEN["open1"],
    "drive": bytes([0x11]) + GOLDEN["vel300"] + GOLDEN["rvel-20"] + GOLDEN["vel2"] + GOLDEN["config1"],
    "sync2_reply": bytes([0x22]) + GOLDEN["sync2_reply"],
    "sip": bytes([0x33]) + SIP + SIP,
    "config": bytes([0x44]) + CONFIG,
    "say": bytes([0x55]) + frame(15, b"\x2B\x05hello\0") + frame(3, b"\x2B\x03\x01\x02\x03\0"),
    # Resynchronisation: 0xFA 0xFA 0xFB, a bad count, a bad checksum, garbage.
    "resync": bytes([0x86]) + b"\x00\xFA" + GOLDEN["sync0"] + b"\xFA\xFB\x02" + GOLDEN["vel300"][:-1] + b"\x00"
              + b"\x13\x37" + GOLDEN["rvel-20"],
}

OUT.mkdir(parents=True, exist_ok=True)
for name, data in SEEDS.items():
    (OUT / name).write_bytes(data)
    print(f"{OUT / name}: {len(data)} bytes")
