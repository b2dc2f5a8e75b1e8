"""A WebSocket client from the standard library, for the tests of tiptap live (RFC 6455:
the opening handshake, masked frames from the client, text, close, ping)."""
import base64
import json
import os
import socket
import struct


class Refused(Exception):
    pass


class WS:
    def __init__(self, port, origin=None, host=None, protocol="tiptap-live", timeout=30, path="/"):
        self.s = socket.create_connection(("127.0.0.1", port), timeout=timeout)
        key = base64.b64encode(os.urandom(16)).decode()
        lines = ["GET %s HTTP/1.1" % path, "Host: %s" % (host or "127.0.0.1:%d" % port),
                 "Upgrade: websocket", "Connection: Upgrade", "Sec-WebSocket-Key: " + key,
                 "Sec-WebSocket-Version: 13"]
        if protocol:
            lines.append("Sec-WebSocket-Protocol: " + protocol)
        if origin:
            lines.append("Origin: " + origin)
        self.s.sendall(("\r\n".join(lines) + "\r\n\r\n").encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.s.recv(4096)
            if not chunk:
                raise Refused("closed during the handshake")
            head += chunk
        head, self.buf = head.split(b"\r\n\r\n", 1)
        if not head.startswith(b"HTTP/1.1 101"):
            raise Refused(head.split(b"\r\n")[0].decode())

    def send(self, text, opcode=1):
        data = text.encode() if isinstance(text, str) else text
        mask = os.urandom(4)
        n = len(data)
        if n < 126:
            hdr = struct.pack("!BB", 0x80 | opcode, 0x80 | n)
        elif n < 65536:
            hdr = struct.pack("!BBH", 0x80 | opcode, 0x80 | 126, n)
        else:
            hdr = struct.pack("!BBQ", 0x80 | opcode, 0x80 | 127, n)
        masked = bytes(b ^ mask[i % 4] for i, b in enumerate(data))
        self.s.sendall(hdr + mask + masked)

    def _read(self, n):
        while len(self.buf) < n:
            chunk = self.s.recv(1 << 16)
            if not chunk:
                raise ConnectionError("the server closed the connection")
            self.buf += chunk
        out, self.buf = self.buf[:n], self.buf[n:]
        return out

    def recv(self):
        """The next text message, parsed (fragments joined; pings answered)."""
        parts = b""
        while True:
            b0, b1 = self._read(2)
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack("!H", self._read(2))[0]
            elif n == 127:
                n = struct.unpack("!Q", self._read(8))[0]
            payload = self._read(n)
            op = b0 & 0x0F
            if op == 8:
                raise ConnectionError("the server closed the WebSocket")
            if op == 9:
                self.send(payload, opcode=10)
                continue
            if op in (0, 1):
                parts += payload
                if b0 & 0x80:
                    return json.loads(parts.decode())

    def recv_type(self, kind, limit=10000):
        for _ in range(limit):
            m = self.recv()
            if m["type"] == kind:
                return m
        raise AssertionError("no %s message in %d" % (kind, limit))

    def close(self):
        try:
            self.send(b"", opcode=8)
        except OSError:
            pass
        self.s.close()


def control(msg, name):
    """The value of control name in a controls message (None: no such control)."""
    for c in msg["controls"]:
        if c["name"] == name:
            return c["value"]
    return None


def ask(ws, text):
    """Send a message; its reply (the other messages in between are skipped)."""
    ws.send(text)
    return ws.recv_type("reply")
