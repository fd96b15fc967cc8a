# SPDX-License-Identifier: MPL-2.0
"""A stand-in for brickEmu's ir-server, written from its documented behaviour only (issue 23): a TCP hub that
relays each chunk it reads from a client to every other client and echoes it to the sender, at once, with no
pacing, no framing and no collisions. Usage: python3 ir_hub.py [PORT] (0 or none: any free port); it prints
"port N" once it listens, and runs until killed. SO_REUSEADDR lets a restarted hub take the same port again.
"""
import select
import socket
import sys


def main():
    listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    listener.bind(("127.0.0.1", int(sys.argv[1]) if len(sys.argv) > 1 else 0))
    listener.listen(16)
    print("port %d" % listener.getsockname()[1], flush=True)
    clients = []
    while True:
        readable, _, _ = select.select([listener] + clients, [], [])
        for s in readable:
            if s is listener:
                c, _ = listener.accept()
                c.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
                clients.append(c)
                continue
            try:
                chunk = s.recv(4096)
            except OSError:
                chunk = b""
            if not chunk:
                clients.remove(s)
                s.close()
                continue
            for c in list(clients):  # the sender included: its echo
                try:
                    c.sendall(chunk)
                except OSError:
                    clients.remove(c)
                    c.close()


if __name__ == "__main__":
    main()
