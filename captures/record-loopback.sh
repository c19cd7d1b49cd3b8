#!/usr/bin/env bash
# Records captures/loopback-real.pcap for real: tcpdump listens on lo while a
# small Python program exchanges TOP frames over real UDP sockets on
# 127.0.0.1 (a client on port 40100, a "gimbal" on port 5000 that echoes
# each write, answers VER, ignores one request and pushes GAC at 20 Hz).
# Needs tcpdump and the right to capture on lo (root or CAP_NET_RAW).
set -euo pipefail
cd "$(dirname "$0")"
out=${1:-loopback-real.pcap}
tcpdump -i lo -U -w "$out" 'udp and (port 5000 or port 40100)' 2>tcpdump.err &
pid=$!
trap 'kill -INT $pid 2>/dev/null || true' EXIT
sleep 1
python3 - <<'PY'
import socket, time

def frame(s):
    return (s + '%02X' % (sum(s.encode('latin1')) % 256)).encode('latin1')

dev = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
dev.bind(('127.0.0.1', 5000))
cli = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
cli.bind(('127.0.0.1', 40100))
to_dev = ('127.0.0.1', 5000)

def exchange(req, resp=None, delay=0.005):
    cli.sendto(frame(req), to_dev)
    data, peer = dev.recvfrom(2048)
    time.sleep(delay)
    if resp is not None:
        dev.sendto(frame(resp) if not isinstance(resp, bytes) else resp, peer)
        cli.recvfrom(2048)
    time.sleep(0.02)

exchange('#TPUD2rVER00', '#tpDU6rVER010502')
exchange('#tpUG6wGAYEC7832', '#tpGU6wGAYEC7832')
exchange('#tpUG6wGAP03E832', '#tpGU6wGAP03E832', delay=0.012)
exchange('#TPUG2wGAA14', '#TPGU2wGAA14')          # attitude push at 20 Hz
peer = ('127.0.0.1', 40100)
for i in range(20):
    dev.sendto(frame('#TPGUCrGAC%04X%04X0000' % (i * 10, 0xFF00 + i)), peer)
    cli.recvfrom(2048)
    time.sleep(0.05)
exchange('#TPUG2wGAA00', '#TPGU2wGAA00')
exchange('#TPUG2wPTZ05', None)                   # never answered
cli.sendto(frame('#TPUG2wPTZ00') + frame('#TPUG2wPTZ05'), to_dev)   # two frames, one datagram
dev.recvfrom(2048)
time.sleep(0.02)
PY
sleep 1
kill -INT $pid
wait $pid || true
trap - EXIT
cat tcpdump.err >&2
rm -f tcpdump.err
echo "wrote $(pwd)/$out"
