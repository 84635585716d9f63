#!/usr/bin/env python3
"""The live web view's real-time factor with and without a stalled browser.

Protocol: `mjarm view MODEL --web --duration SECONDS --json` runs twice on this machine, once with
no client and once with a client that completes the WebSocket handshake, shrinks its receive
buffer to 4 KiB and never reads again (a browser tab frozen in a debugger). Each run prints its
real-time factor (simulated time / wall time), the frames published, sent and skipped, and the
clients still connected at the end (the server closes one that has not answered its pings for
20 s). The stalled client must cost the simulation nothing: both factors near 1.

    python3 bench/web_stalled_client.py build-rel/mjarm [--model panda] [--seconds 10] [--json]

MJARM is a CLI built with the live page (MJARM_WEB, docs/replay.md): without it `view --web`
exits 1 and so does this.
"""

import argparse
import base64
import json
import os
import re
import socket
import subprocess
import sys
import time


def start_viewer(mjarm, model, seconds):
    process = subprocess.Popen(
        [mjarm, "view", model, "--web", "--duration", str(seconds), "--json"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = process.stderr.readline()
    found = re.search(r"http://([0-9.]+):(\d+)/", line)
    if not found:
        process.kill()
        sys.exit(f"the viewer did not print its address: {line!r}")
    return process, found.group(1), int(found.group(2))


def stalled_client(host, port):
    """A WebSocket client that shakes hands and then never reads."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)  # before connecting: a small window
    sock.connect((host, port))
    key = base64.b64encode(os.urandom(16)).decode()
    sock.sendall((f"GET /ws HTTP/1.1\r\nHost: {host}:{port}\r\nUpgrade: websocket\r\n"
                  f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                  "Sec-WebSocket-Version: 13\r\n\r\n").encode())
    answer = b""
    while b"\r\n\r\n" not in answer:
        chunk = sock.recv(1)
        if not chunk:
            sys.exit("the server closed the connection during the handshake")
        answer += chunk
    if not answer.startswith(b"HTTP/1.1 101"):
        sys.exit(f"the handshake was refused: {answer[:80]!r}")
    return sock  # never read from again


def run(mjarm, model, seconds, stall):
    process, host, port = start_viewer(mjarm, model, seconds)
    client = stalled_client(host, port) if stall else None
    out, err = process.communicate(timeout=seconds + 120)
    if client:
        client.close()
    if process.returncode != 0:
        sys.exit(f"the viewer failed ({process.returncode}): {err}")
    report = json.loads(out)
    server = report["server"]
    return {"stalled_client": stall, "real_time_factor": report["real_time_factor"],
            "sim_time": report["sim_time"], "wall_seconds": report["wall_seconds"],
            "dropped_sim_time": report["dropped_sim_time"], "published": server["published"],
            "sent": server["sent"], "skipped": server["skipped"],
            "connections": server["connections"], "clients_at_end": server["clients"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mjarm")
    parser.add_argument("--model", default="panda")
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    if not 1.0 <= args.seconds <= 3600.0:
        parser.error("--seconds: 1 to 3600")
    runs = [run(args.mjarm, args.model, args.seconds, stall) for stall in (False, True)]
    if args.json:
        print(json.dumps(runs, indent=2))
        return
    print(f"mjarm view {args.model} --web, {args.seconds:g} s each")
    print(f"{'client':<16}{'real-time factor':>18}{'dropped [s]':>13}{'published':>11}"
          f"{'sent':>8}{'skipped':>9}{'connected at end':>18}")
    for r in runs:
        name = "stalled" if r["stalled_client"] else "none"
        print(f"{name:<16}{r['real_time_factor']:>18.4f}{r['dropped_sim_time']:>13.3f}"
              f"{r['published']:>11}{r['sent']:>8}{r['skipped']:>9}{r['clients_at_end']:>18}")


if __name__ == "__main__":
    main()
