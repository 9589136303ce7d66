"""Edits the JSON header of a shard file of `sphbasis bake --shard` (docs/bake-format.md) and
writes it back with a valid checksum, computed with XXH3-64 from the system's libxxhash (an
independent computation of the format's checksum), so that bake-merge's header checks are
reached: python3 edit_shard.py SHARD KEY VALUE (VALUE: JSON, or DELETE to remove KEY)."""
import ctypes
import json
import struct
import sys

lib = ctypes.CDLL("libxxhash.so.0")
lib.XXH3_64bits.restype = ctypes.c_uint64
lib.XXH3_64bits.argtypes = [ctypes.c_char_p, ctypes.c_size_t]

path, key, value = sys.argv[1], sys.argv[2], sys.argv[3]
b = open(path, "rb").read()
assert b[:8] == b"SPHBFILE", "not a bake file"
payload = b[40:]
assert struct.unpack("<Q", b[24:32])[0] == len(payload)
assert struct.unpack("<Q", b[32:40])[0] == lib.XXH3_64bits(b[:32] + payload, 32 + len(payload))
n = struct.unpack("<Q", payload[:8])[0]
header = json.loads(payload[8:8 + n])
if value == "DELETE":
    header.pop(key)
else:
    header[key] = json.loads(value)
text = json.dumps(header).encode()
payload = struct.pack("<Q", len(text)) + text + payload[8 + n:]
head = b[:24] + struct.pack("<Q", len(payload))
checksum = lib.XXH3_64bits(head + payload, len(head) + len(payload))
open(path, "wb").write(head + struct.pack("<Q", checksum) + payload)
