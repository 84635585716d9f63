"""mjarm.viewer.launch_passive(..., web=True) on the user's own mujoco objects, with no display:
a browser (a WebSocket client written here on the standard library) gets the greeting (the model
as the replay page draws it) and then the frames of the bodies the loop moves; the token off
loopback; closing; the errors. A build without the page (MJARM_WEB) refuses, saying how to get it."""
import base64
import json
import os
import socket
import struct
import urllib.error
import urllib.request

import mujoco
import numpy as np
import pytest

import mjarm
import mjarm.viewer

FALLING_BOX = """
<mujoco model="falling_box">
  <option timestep="0.002"/>
  <worldbody>
    <body name="box" pos="0 0 1">
      <freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="1"/>
    </body>
  </worldbody>
</mujoco>
"""


class Browser:
    """The WebSocket end of a page: the handshake, then whole messages (text or binary)."""

    def __init__(self, url):
        host_port, _, rest = url[len("http://"):].partition("/")
        host, port = host_port.rsplit(":", 1)
        self.sock = socket.create_connection((host, int(port)), timeout=60)
        key = base64.b64encode(os.urandom(16)).decode()
        query = rest[rest.index("?"):] if "?" in rest else ""
        self.sock.sendall((f"GET /ws{query} HTTP/1.1\r\nHost: {host_port}\r\n"
                           "Upgrade: websocket\r\nConnection: Upgrade\r\n"
                           f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n").encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(1)
            assert chunk, "closed during the handshake"
            head += chunk
        self.status = int(head.split(b" ", 2)[1])

    def _exactly(self, n):
        data = b""
        while len(data) < n:
            chunk = self.sock.recv(n - len(data))
            assert chunk, "the server closed the connection"
            data += chunk
        return data

    def read(self):
        """(is_text, payload) of the next data message, its fragments joined (a greeting with
        the model's meshes and textures comes in several); pings and pongs are skipped."""
        message, is_text = None, False
        while True:
            first, second = self._exactly(2)
            length = second & 0x7F
            if length == 126:
                length = struct.unpack(">H", self._exactly(2))[0]
            elif length == 127:
                length = struct.unpack(">Q", self._exactly(8))[0]
            payload = self._exactly(length)
            opcode = first & 0x0F
            if opcode in (1, 2):
                message, is_text = payload, opcode == 1
            elif opcode == 0 and message is not None:
                message += payload
            else:
                continue  # a control frame
            if first & 0x80:  # the message's last fragment
                return is_text, message

    def close(self):
        self.sock.close()


def page_available(model, data):
    """True when this build serves the page; else checks the refusal says how to get it."""
    try:
        mjarm.viewer.launch_passive(model, data, web=True).close()
        return True
    except mjarm.Error as error:
        assert "passive web viewer: this mjarm was built without the replay page" in str(error)
        assert "-DMJARM_WEB=ON" in str(error)
        return False


def test_a_browser_sees_the_bodies_the_loop_moves():
    model = mujoco.MjModel.from_xml_string(FALLING_BOX)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    if not page_available(model, data):
        return
    with mjarm.viewer.launch_passive(model, data, web=True) as viewer:
        assert viewer.url.startswith("http://127.0.0.1:")
        assert "token" not in viewer.url
        page = urllib.request.urlopen(viewer.url, timeout=60).read().decode()
        assert "<title>mjarm live view</title>" in page
        assert 'id="mjarm-live"' in page
        browser = Browser(viewer.url)
        assert browser.status == 101
        is_text, greeting = browser.read()
        assert is_text
        greeting = json.loads(greeting)
        assert [b["name"] for b in greeting["bodies"]] == ["world", "box"]
        assert [g["type"] for g in greeting["geoms"]] == ["box"]  # what the page draws
        layout = greeting["frame"]
        assert "tool" not in layout  # watched, not steered: no panel
        assert (layout["floats"], layout["pos"], layout["quat"]) == (15, 1, 7)
        viewer.sync()
        _, frame = browser.read()
        first = np.frombuffer(frame, dtype="<f4")
        assert first.shape == (15,)
        assert first[layout["pos"] + 3 + 2] == pytest.approx(1.0)  # the box's height
        for _ in range(250):  # half a second of falling
            mujoco.mj_step(model, data)
        mujoco.mj_forward(model, data)
        viewer.sync()
        _, frame = browser.read()
        last = np.frombuffer(frame, dtype="<f4")
        assert last[0] == pytest.approx(data.time, rel=1e-6)
        pos = last[layout["pos"]:layout["quat"]].reshape(2, 3)
        quat = last[layout["quat"]:].reshape(2, 4)
        assert pos == pytest.approx(data.xpos, abs=1e-6)
        assert quat == pytest.approx(data.xquat, abs=1e-6)
        assert pos[1, 2] < 1.0 - 0.5 * 9.81 * 0.45 ** 2  # it fell
        assert viewer.syncs == 2
        assert viewer.stats["connections"] == 1
        browser.close()
    assert not viewer.is_running()
    assert viewer.url == ""
    viewer.sync()  # nothing once closed


def test_off_loopback_the_token_is_needed():
    model = mujoco.MjModel.from_xml_string(FALLING_BOX)
    data = mujoco.MjData(model)
    if not page_available(model, data):
        return
    with mjarm.viewer.launch_passive(model, data, web=True, host="0.0.0.0") as viewer:
        token = viewer.url.split("?token=")[1]
        assert len(token) == 32
        bare = viewer.url.split("?")[0].replace("0.0.0.0", "127.0.0.1")
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(bare, timeout=60)
        assert refused.value.code == 403
        assert Browser(bare).status == 403
        assert Browser(bare + "?token=" + "0" * 32).status == 403
        assert Browser(bare + "?token=" + token).status == 101
        assert viewer.stats["refused"] == 3


def test_bad_input_is_refused():
    model = mujoco.MjModel.from_xml_string(FALLING_BOX)
    data = mujoco.MjData(model)
    other = mujoco.MjModel.from_xml_string(FALLING_BOX.replace("<freejoint/>", ""))
    with pytest.raises(mjarm.Error, match="model"):
        mjarm.viewer.launch_passive(model, mujoco.MjData(other), web=True)
    if page_available(model, data):  # else the page's absence is said first
        with pytest.raises(mjarm.Error, match="is not an IP address"):
            mjarm.viewer.launch_passive(model, data, web=True, host="nowhere")
    with pytest.raises(TypeError, match="web=True"):
        mjarm.viewer.launch_passive(model, data, web=True, script="wait 1")
