"""What the bench reports name: the CPU model and the commit of the code run
(bench.py, pareto.py, roofline.py)."""

import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cpu_model():
    """The CPU's model name, with what tells two CPUs of the same name apart
    (the shared machines all call themselves "AMD EPYC"): its family and
    model, its widest vector instructions, its L2 per core, e.g.
    "AMD EPYC (family 25, model 1; AVX2 + FMA, no AVX-512; L2 512 KiB per core)"."""
    info = {}
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if not line.strip():
                    break    # the first processor's block
                k, _, v = line.partition(":")
                info[k.strip()] = v.strip()
    except OSError:
        return "?"
    name = info.get("model name", "?")
    flags = info.get("flags", "").split()
    if "avx512f" in flags:
        isa = "AVX-512"
    elif "avx2" in flags:
        isa = "AVX2" + (" + FMA" if "fma" in flags else "") + ", no AVX-512"
    else:
        isa = "no AVX2"
    parts = []
    if "cpu family" in info and "model" in info:
        parts.append(f"family {info['cpu family']}, model {info['model']}")
    l2 = ""
    try:
        with open("/sys/devices/system/cpu/cpu0/cache/index2/size") as f:
            l2 = f.read().strip()
    except OSError:
        pass
    tail = isa + (f"; L2 {l2.replace('K', ' KiB').replace('M', ' MiB')} per core" if l2 else "")
    return f"{name} ({'; '.join(parts + [tail])})"


def commit():
    """git describe --always --dirty of the checkout ('?' outside git)"""
    try:
        return subprocess.run(["git", "-C", ROOT, "describe", "--always", "--dirty"],
                              capture_output=True, text=True).stdout.strip() or "?"
    except OSError:
        return "?"
