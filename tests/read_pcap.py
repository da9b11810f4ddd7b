#!/usr/bin/python3
"""Reads a libpcap capture of UDP datagrams with nothing but python's struct (the independent
reader of the C++ tests): checks the global header, each frame's Ethernet/IPv4/UDP headers and
both checksums, writes the UDP payloads one after the other to PAYLOADS, and prints one JSON
object. Usage: read_pcap.py FILE.pcap PAYLOADS
"""
import json
import socket
import struct
import sys


def checksum(data):
    if len(data) % 2:
        data += b"\0"
    total = sum(struct.unpack("!%dH" % (len(data) // 2), data))
    while total >> 16:
        total = (total & 0xFFFF) + (total >> 16)
    return total  # 0xFFFF when the stored checksum is right


def main(path, payload_path):
    raw = open(path, "rb").read()
    magic, major, minor, _, _, snaplen, linktype = struct.unpack_from("<IHHiIII", raw, 0)
    out = {"magic": "%08x" % magic, "version": [major, minor], "snaplen": snaplen, "linktype": linktype,
           "packets": 0, "bad_ip_checksums": 0, "bad_udp_checksums": 0, "ports": [], "source": None}
    at = 24
    payloads = []
    while at + 16 <= len(raw):
        sec, usec, incl, orig = struct.unpack_from("<IIII", raw, at)
        at += 16
        frame = raw[at:at + incl]
        at += incl
        if out["packets"] == 0:
            out["first_stamp"] = sec + usec * 1e-6
        out["packets"] += 1
        (ethertype,) = struct.unpack_from("!H", frame, 12)
        assert ethertype == 0x0800, "not IPv4"
        ip = frame[14:34]
        if checksum(ip) != 0xFFFF:
            out["bad_ip_checksums"] += 1
        src, dst = ip[12:16], ip[16:20]
        out["source"] = socket.inet_ntoa(src)
        udp = frame[34:]
        sport, dport, length, _ = struct.unpack_from("!HHHH", udp, 0)
        pseudo = src + dst + struct.pack("!BBH", 0, ip[9], length)
        if checksum(pseudo + udp[:length]) != 0xFFFF:
            out["bad_udp_checksums"] += 1
        if [sport, dport] not in out["ports"]:
            out["ports"].append([sport, dport])
        payloads.append(udp[8:length])
    with open(payload_path, "wb") as f:
        f.write(b"".join(payloads))
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
