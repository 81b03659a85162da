#!/usr/bin/env python3
"""fatbin_check.py FILE ARCH...: the GPU code in FILE's .nv_fatbin section (a
library or an executable built by nvcc), listed as `cuobjdump --list-elf` /
`--list-ptx` would (CUDA 13 fat binaries, read here as this toolkit may lack
cuobjdump); exit 1 unless every ARCH (sm_90, compute_90, ...) is there.
Used by scripts/build-lammps-plugin.sh (kokkos-cuda, bundle-cuda)."""
import collections, os, struct, subprocess, sys, tempfile
so, want = sys.argv[1], sys.argv[2:]
with tempfile.TemporaryDirectory() as d:
    subprocess.run(["objcopy", "-O", "binary", "--only-section=.nv_fatbin", so,
                    os.path.join(d, "f")], check=True)
    data = open(os.path.join(d, "f"), "rb").read()
# containers: u32 magic 0xBA55ED50, u16 version, u16 header size, u64 size;
# then entries: u16 kind (1 PTX, 2 ELF), u16, u32 entry header size, u64
# payload size, ..., u32 at byte 28: the arch; the payload follows. An
# uncompressed ELF payload (a cubin) has its arch in e_flags bits 8-15.
count, fatbins, p, bad = collections.Counter(), 0, 0, 0
magic = struct.pack("<I", 0xBA55ED50)
while True:
    p = data.find(magic, p)
    if p < 0:
        break
    _, _, hsize, size = struct.unpack_from("<IHHQ", data, p)
    q, end, fatbins = p + hsize, p + hsize + size, fatbins + 1
    while q + 32 <= end:
        kind, _, ehsize, psize = struct.unpack_from("<HHIQ", data, q)
        if ehsize == 0:
            break
        arch = struct.unpack_from("<I", data, q + 28)[0]
        pl = data[q + ehsize:q + ehsize + 64]
        if kind == 2 and pl[:4] == b"\x7fELF" and (struct.unpack_from("<I", pl, 48)[0] >> 8) & 0xff != arch:
            bad += 1
        count[{1: "compute_%d", 2: "sm_%d"}.get(kind, "kind%d_" % kind + "%d") % arch] += 1
        q += ehsize + psize
    p = end
print("fatbin_check.py: %s: %d fat binaries in .nv_fatbin (%d bytes): %s" % (
    os.path.basename(so), fatbins, len(data),
    ", ".join("%s %d" % (k.replace("sm_", "ELF sm_").replace("compute_", "PTX compute_"), n)
              for k, n in sorted(count.items()))))
missing = [w for w in want if not count[w]]
if missing or bad:
    sys.exit("no GPU code for %s; %d cubins whose ELF arch differs" % (" ".join(missing) or "-", bad))
