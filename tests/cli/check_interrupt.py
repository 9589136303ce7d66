#!/usr/bin/env python3
"""Interrupts a `sphbasis` run while it works (tests/cli/output_tests.cmake).

Usage: check_interrupt.py SIGNAL DIR COMMAND [ARG ...]

Starts COMMAND, waits (at most 60 s) until DIR holds a staging directory of the tool
(".sphbasis-staging-*": the outputs were checked and the work has begun), waits 0.3 s more, sends
SIGNAL (INT, TERM or KILL) and waits for the end. Prints one line
    status N seconds S staging-left K
N: the exit status as a shell reports it (128 + the signal when the process was killed by one),
S: seconds from the signal to the end, K: staging directories left in DIR. Exits 1 (with a
line saying why) when no staging directory appeared or the command did not end within 30 s.
The child gets the default action of SIGINT even where this script is started in the
background of a shell (which ignores SIGINT there): subprocess restores it.
"""
import os
import signal
import subprocess
import sys
import time


def stagings(d):
    try:
        return [f for f in os.listdir(d) if f.startswith(".sphbasis-staging-")]
    except OSError:
        return []


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    sig = getattr(signal, "SIG" + sys.argv[1])
    d = sys.argv[2]
    p = subprocess.Popen(sys.argv[3:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    t0 = time.monotonic()
    while not stagings(d):
        if p.poll() is not None:
            print("ended (status %d) before staging anything" % p.returncode)
            return 1
        if time.monotonic() - t0 > 60:
            p.kill()
            print("no staging directory in %s after 60 s" % d)
            return 1
        time.sleep(0.02)
    time.sleep(0.3)
    if p.poll() is not None:
        print("ended (status %d) before the signal" % p.returncode)
        return 1
    t1 = time.monotonic()
    p.send_signal(sig)
    try:
        rc = p.wait(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill()
        print("did not stop within 30 s of the signal")
        return 1
    status = 128 - rc if rc < 0 else rc
    print("status %d seconds %.3f staging-left %d" % (status, time.monotonic() - t1,
                                                      len(stagings(d))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
