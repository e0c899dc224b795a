#!/usr/bin/env python3
"""Fault campaign (docs/executive.md, "Fault campaign"): short relay missions on
real processes (p3at_sim --speedup, two mission_exec over LCM on the loopback)
under faults drawn from a seed, with invariants checked after each:

  - no motion after a refusal: if a robot's gate refused (exit 4, 5, 6), the
    simulator counted no motion command for either robot;
  - a dead link stops the robot: after the simulator is frozen past the link-loss
    time, or a robot is killed or frozen past the watchdog, the robot it drove
    receives no further motion and stands still within the firmware watchdog;
  - exit statuses as documented (0, 3, 4, 5, 6, 8; 0 for both without a fault);
  - no crash (no process ends by a signal we did not send), no hang past a bound.

Faults: kill or SIGSTOP the simulator or a robot at a random time, drop or delay
team datagrams through a loss proxy between the two robots' LCM groups, restart
a robot during its gate, a NO-GO robot, a late robot. Each robot talks LCM on its
own multicast port; the proxy (this script) forwards between the two with the
fault's loss and delay, so the robots hear each other only through it.

Usage: scripts/fault-campaign.py [--bin build/release/bin] [--seed N] [--faults 50] [--jobs 2]
The seed and, for each failed fault, its logs are printed. Exit 0 when every
invariant held, 1 otherwise. Python 3 standard library only.
"""

import argparse
import concurrent.futures
import hashlib
import os
import random
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MISSION = os.path.join(ROOT, "examples/relay/mission.yaml")
WORLD = os.path.join(ROOT, "examples/relay/world.yaml")
MODELS = os.path.join(ROOT, "tests/sitl/data/relay_models.yaml")
GROUP = "239.255.76.67"
SPEEDUP = 5.0
WATCHDOG_S = 2.0          # firmware watchdog, controller seconds
LINK_LOSS_S = 1.0         # mission_exec: no SIP for this long (wall) = link lost
GATE_TIMEOUT_S = 5.0
HANG_BOUND_S = 45.0       # no process may run longer than this
DOCUMENTED = {0, 3, 4, 5, 6, 8}
REFUSALS = {4, 5, 6}

FAULTS = ["none", "kill_sim", "stop_sim", "kill_robot", "stop_robot", "drop", "delay",
          "restart_robot", "no_go", "late_robot"]


class LossProxy:
    """Forwards LCM datagrams between two multicast ports on the loopback,
    dropping each with probability `loss` and delaying it by `delay_s` (plus
    jitter). Datagrams it sent itself (heard back by multicast) are ignored."""

    def __init__(self, port_a, port_b, rng):
        self.ports = (port_a, port_b)
        self.loss = 0.0
        self.delay_s = 0.0
        self.rng = rng
        self.sent = {}
        self.forwarded = 0
        self.dropped = 0
        self.lock = threading.Lock()
        self.stop = threading.Event()
        self.out = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.out.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
        self.out.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
        self.out.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton("127.0.0.1"))
        self.socks = [self._listen(p) for p in self.ports]
        self.threads = [threading.Thread(target=self._run, args=(i,), daemon=True) for i in range(2)]
        for t in self.threads:
            t.start()

    @staticmethod
    def _listen(port):
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        s.bind(("", port))
        mreq = struct.pack("4s4s", socket.inet_aton(GROUP), socket.inet_aton("127.0.0.1"))
        s.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, mreq)
        s.settimeout(0.1)
        return s

    def _send_later(self, data, port, at):
        def go():
            delay = at - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            if not self.stop.is_set():
                self.out.sendto(data, (GROUP, port))
        if at <= time.monotonic():
            go()
        else:
            threading.Thread(target=go, daemon=True).start()

    def _run(self, i):
        sock, other = self.socks[i], self.ports[1 - i]
        while not self.stop.is_set():
            try:
                data = sock.recv(65536)
            except socket.timeout:
                continue
            except OSError:
                return
            digest = hashlib.blake2b(data, digest_size=16).digest()
            with self.lock:
                if self.sent.pop(digest, None) is not None:
                    continue  # our own forward, heard back
                if self.rng.random() < self.loss:
                    self.dropped += 1
                    continue
                self.sent[digest] = time.monotonic()
                if len(self.sent) > 20000:
                    self.sent.clear()
                self.forwarded += 1
                delay = self.delay_s * (0.5 + self.rng.random()) if self.delay_s > 0 else 0.0
            self._send_later(data, other, time.monotonic() + delay)

    def close(self):
        self.stop.set()
        for t in self.threads:
            t.join(1.0)
        for s in self.socks + [self.out]:
            s.close()


# Ports handed out to trials so far: with --jobs, trials run side by side, and a
# port one trial picked but its simulator has not bound yet looks free to the next.
_PORTS_LOCK = threading.Lock()
_PORTS_TAKEN = set()


def free_port_pair():
    with _PORTS_LOCK:
        for _ in range(200):
            p = _free_port_pair_once()
            if p is not None and p not in _PORTS_TAKEN and p + 1 not in _PORTS_TAKEN:
                _PORTS_TAKEN.update((p, p + 1))
                return p
    raise RuntimeError("no free TCP port pair")


def lcm_port_pair(base):
    """The trial's pair of LCM ports from its drawn base, moved on past pairs
    another trial holds (the draw stays the seed's, whatever --jobs is)."""
    with _PORTS_LOCK:
        while base in _PORTS_TAKEN or base + 1 in _PORTS_TAKEN:
            base = 20000 + (base - 20000 + 2) % 40000
        _PORTS_TAKEN.update((base, base + 1))
        return base


def _free_port_pair_once():
    """A TCP port the kernel calls free whose next one is free too (the
    simulator serves robot1 on it and robot2 on the next), or None."""
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    if p >= 65000:
        return None
    t = socket.socket()
    try:
        t.bind(("127.0.0.1", p + 1))
        return p
    except OSError:
        return None
    finally:
        t.close()


def truth_rows(path, robot):
    rows = []
    try:
        with open(path) as f:
            for line in f:
                parts = line.strip().split(",")
                if len(parts) == 11 and parts[1] == robot:
                    try:
                        rows.append((float(parts[0]), float(parts[8]), float(parts[9]), int(parts[10])))
                    except ValueError:
                        pass
    except FileNotFoundError:
        pass
    return rows  # (time_s, trans_vel, rot_vel, motion_commands)


class Proc:
    def __init__(self, name, argv, logdir):
        self.name = name
        self.log_path = os.path.join(logdir, name + ".log")
        self.log = open(self.log_path, "w")
        self.p = subprocess.Popen(argv, stdout=self.log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
        self.signalled = None  # the signal we sent, if any
        self.started = time.monotonic()

    def send(self, sig):
        if self.p.poll() is None:
            if sig in (signal.SIGKILL, signal.SIGTERM):
                self.signalled = sig
            self.p.send_signal(sig)

    def text(self):
        self.log.flush()
        with open(self.log_path, errors="replace") as f:
            return f.read()

    def wait(self, deadline):
        try:
            return self.p.wait(timeout=max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            return None


def wait_for(pred, timeout_s):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if pred():
            return True
        time.sleep(0.02)
    return pred()


class Trial:
    def __init__(self, args, index, fault, rng, keyfile, mission, tmp):
        self.args, self.index, self.fault, self.rng = args, index, fault, rng
        self.keyfile, self.mission = keyfile, mission
        self.dir = os.path.join(tmp, "fault-%03d-%s" % (index, fault))
        os.makedirs(self.dir)
        self.notes = []
        self.failures = []
        self.procs = []
        self.killed = set()      # processes we killed (their exit is not a crash)
        self.checks = []         # (robot, sim_time_from) : must stand still from then on

    def bin(self, name):
        return os.path.join(self.args.bin, name)

    def robot_args(self, robot, port, lcm_port, extra=()):
        hal_port = port if robot == "robot1" else port + 1
        return [self.bin("mission_exec"), "--robot", robot, "--mission", self.mission, "--models", MODELS,
                "--hal", "tcp://127.0.0.1:%d" % hal_port, "--lcm", "udpm://%s:%d?ttl=0" % (GROUP, lcm_port),
                "--team-key", self.keyfile, "--gate-timeout", str(GATE_TIMEOUT_S), "--linger-s", "1",
                "--teammate-silence-s", "1.5", "--overtime-s", "10", "--log-level", "info"] + list(extra)

    def start_robot(self, robot, extra=(), tag=""):
        lcm_port = self.lcm1 if robot == "robot1" else self.lcm2
        p = Proc(robot + tag, self.robot_args(robot, self.port, lcm_port, extra), self.dir)
        self.procs.append(p)
        return p

    def sim_time(self):
        rows = truth_rows(self.truth, "robot1")
        return rows[-1][0] if rows else 0.0

    def motion(self, robot):
        rows = truth_rows(self.truth, robot)
        return rows[-1][3] if rows else 0

    def run(self):
        rng = self.rng
        self.port = free_port_pair()
        base = lcm_port_pair(20000 + rng.randrange(20000) * 2)
        self.lcm1, self.lcm2 = base, base + 1
        self.truth = os.path.join(self.dir, "truth.csv")
        proxy = LossProxy(self.lcm1, self.lcm2, random.Random(rng.random()))
        sim = Proc("p3at_sim", [self.bin("p3at_sim"), "--world", WORLD, "--speedup", str(SPEEDUP), "--port",
                                str(self.port), "--truth-csv", self.truth], self.dir)
        self.sim = sim
        try:
            if not wait_for(lambda: "port=%d" % (self.port + 1) in sim.text(), 10):
                self.failures.append("p3at_sim did not start")
                return
            self.inject(proxy)
        finally:
            for p in self.procs:
                if p.p.poll() is None:
                    p.wait(time.monotonic() + 0.1)
            deadline = min(p.started for p in self.procs) + HANG_BOUND_S if self.procs else time.monotonic()
            for p in self.procs:
                if p.wait(deadline) is None:
                    self.failures.append("%s hung past %.0f s" % (p.name, HANG_BOUND_S))
                    p.send(signal.SIGKILL)
                    self.killed.add(p)
                    p.wait(time.monotonic() + 5)
            if sim.p.poll() is None:
                sim.send(signal.SIGTERM)
                if sim.wait(time.monotonic() + 10) is None:
                    sim.send(signal.SIGKILL)
            proxy.close()
            self.notes.append("proxy forwarded=%d dropped=%d" % (proxy.forwarded, proxy.dropped))
        self.check()

    def inject(self, proxy):
        rng, f = self.rng, self.fault
        r2_extra = ["--tmax", "5"] if f == "no_go" else []
        if f == "drop":
            proxy.loss = rng.uniform(0.2, 0.95)
            self.notes.append("loss=%.2f" % proxy.loss)
        if f == "delay":
            proxy.delay_s = rng.uniform(0.05, 0.8)
            self.notes.append("delay_s=%.2f" % proxy.delay_s)
        r1 = self.start_robot("robot1")
        if f == "late_robot":
            late = rng.uniform(0.0, GATE_TIMEOUT_S + 2.0)
            self.notes.append("robot2 starts %.2f s late" % late)
            time.sleep(late)
        r2 = self.start_robot("robot2", r2_extra)
        robots = {"robot1": r1, "robot2": r2}
        at = rng.uniform(0.2, 3.0)  # from the gate into the mission (about 3 s of wall time at 5x)
        if f in ("kill_sim", "stop_sim", "kill_robot", "stop_robot", "restart_robot"):
            self.notes.append("at %.2f s" % at)
            time.sleep(at)
        if f == "kill_sim":
            self.sim.send(signal.SIGKILL)
            self.killed.add(self.sim)
        elif f == "stop_sim":
            d = rng.uniform(0.3, 2.5)
            self.notes.append("simulator frozen %.2f s" % d)
            before = {r: self.motion(r) for r in robots}
            self.sim.send(signal.SIGSTOP)
            time.sleep(d)
            self.sim.send(signal.SIGCONT)
            if d > LINK_LOSS_S + 0.3:
                self.stop_sim_before = before  # the robots lost their link: no motion after it
        elif f in ("kill_robot", "stop_robot"):
            who = rng.choice(["robot1", "robot2"])
            t_sim = self.sim_time()
            if f == "kill_robot":
                robots[who].send(signal.SIGKILL)
                self.killed.add(robots[who])
                self.notes.append("killed %s at sim t=%.1f" % (who, t_sim))
                self.checks.append((who, t_sim + WATCHDOG_S + 0.5))
            else:
                d = rng.uniform(0.1, 3.0)
                robots[who].send(signal.SIGSTOP)
                time.sleep(d)
                robots[who].send(signal.SIGCONT)
                self.notes.append("froze %s %.2f s at sim t=%.1f" % (who, d, t_sim))
                if d * SPEEDUP > WATCHDOG_S + 1.0:
                    # Frozen past the watchdog: standing still 2.5 s of sim time after the freeze began.
                    self.stopped_robot = (who, t_sim + WATCHDOG_S + 0.5, t_sim + d * SPEEDUP - 0.5)
        elif f == "restart_robot":
            who = rng.choice(["robot1", "robot2"])
            robots[who].send(signal.SIGKILL)
            self.killed.add(robots[who])
            robots[who].wait(time.monotonic() + 5)
            self.notes.append("restarted %s" % who)
            self.start_robot(who, r2_extra if who == "robot2" else (), tag="-restarted")

    def check(self):
        exits = {}
        for p in self.procs:
            rc = p.p.returncode
            exits[p.name] = rc
            if p in self.killed:
                continue
            if rc is None:
                continue  # reported as a hang
            if rc < 0:
                self.failures.append("%s crashed: signal %d" % (p.name, -rc))
            elif rc not in DOCUMENTED:
                self.failures.append("%s exit %d is not a documented status" % (p.name, rc))
        self.notes.append("exits " + " ".join("%s=%s" % kv for kv in exits.items()))
        if self.sim in self.killed:
            return  # the simulator's counters died with it
        m1, m2 = self.motion("robot1"), self.motion("robot2")
        self.notes.append("motion robot1=%d robot2=%d" % (m1, m2))
        refused = [n for n, rc in exits.items() if rc in REFUSALS]
        committed_killed = any(p in self.killed and "event=gate-commit" in p.text() for p in self.procs)
        if refused and not committed_killed and (m1 > 0 or m2 > 0):
            self.failures.append("INVARIANT: %s refused, yet motion robot1=%d robot2=%d" % (",".join(refused), m1, m2))
        if self.fault == "none" and any(rc != 0 for rc in exits.values()):
            self.failures.append("without a fault both robots must finish (exit 0)")
        if self.fault == "no_go":
            for n, rc in exits.items():
                if rc != 4:
                    self.failures.append("%s: a NO-GO teammate must refuse the launch (exit 4), got %s" % (n, rc))
        before = getattr(self, "stop_sim_before", None)
        if before:
            for r, b in before.items():
                if self.motion(r) - b > 6:
                    self.failures.append("INVARIANT: %s received %d motion commands after its link died" %
                                         (r, self.motion(r) - b))
        checks = list(self.checks)
        frozen = getattr(self, "stopped_robot", None)
        for who, from_t in checks:
            moving = [row for row in truth_rows(self.truth, who) if row[0] >= from_t and (row[1] != 0 or row[2] != 0)]
            if moving:
                self.failures.append("INVARIANT: %s still moving at sim t=%.1f, past the watchdog after its "
                                     "process died" % (who, moving[0][0]))
        if frozen:
            who, from_t, to_t = frozen
            moving = [row for row in truth_rows(self.truth, who)
                      if from_t <= row[0] <= to_t and (row[1] != 0 or row[2] != 0)]
            if moving:
                self.failures.append("INVARIANT: %s still moving at sim t=%.1f while its process was frozen past "
                                     "the watchdog" % (who, moving[0][0]))

    def report(self):
        out = ["--- fault %d: %s (%s)" % (self.index, self.fault, "; ".join(self.notes))]
        for f in self.failures:
            out.append("    FAIL: " + f)
        if self.failures:
            for p in [self.sim] + self.procs:
                out.append("    ---- log of %s (%s):" % (p.name, p.log_path))
                out.extend("      " + line for line in p.text().splitlines()[-60:])
        return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build/release/bin"))
    ap.add_argument("--seed", type=int, default=None, help="default: from the clock (printed)")
    ap.add_argument("--faults", type=int, default=50)
    ap.add_argument("--keep", action="store_true", help="keep the logs of passing faults too")
    ap.add_argument("--jobs", type=int, default=1,
                    help="trials run side by side (each on its own ports; the faults and their draws are the "
                         "seed's whatever this is); results are printed in fault order")
    args = ap.parse_args()
    seed = args.seed if args.seed is not None else int(time.time()) % 1000000
    rng = random.Random(seed)
    print("fault-campaign: seed=%d faults=%d jobs=%d speedup=%g (rerun: %s --seed %d --faults %d --jobs %d)" %
          (seed, args.faults, args.jobs, SPEEDUP, sys.argv[0], seed, args.faults, args.jobs), flush=True)
    tmp = tempfile.mkdtemp(prefix="p3at-fault-campaign-")
    keyfile = os.path.join(tmp, "team.key")
    subprocess.run([os.path.join(args.bin, "p3at_team_key"), keyfile], check=True, stdout=subprocess.DEVNULL)
    # The relay with abort_action: stop_and_notify, so a survivor stops at once.
    mission = os.path.join(tmp, "relay.yaml")
    with open(MISSION) as f:
        text = f.read()
    text = text.replace("  threshold: 0.8", "  threshold: 0.8\n  abort_action: stop_and_notify", 1)
    with open(mission, "w") as f:
        f.write(text)
    start = time.monotonic()
    failed = 0
    counts = {}
    # Every trial's fault and random stream are drawn first, in order, so a
    # seed names the same campaign at any --jobs.
    trials = []
    for i in range(args.faults):
        fault = FAULTS[i % len(FAULTS)] if i < len(FAULTS) else rng.choice(FAULTS)
        counts[fault] = counts.get(fault, 0) + 1
        trials.append(Trial(args, i, fault, random.Random(rng.random()), keyfile, mission, tmp))

    def run_one(trial):
        try:
            trial.run()
        except Exception as e:  # the driver's own trouble is a failure too, never a pass
            trial.failures.append("driver error: %r" % (e,))
        return trial

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for trial in pool.map(run_one, trials):  # in fault order, each as soon as it and those before are done
            if trial.failures:
                failed += 1
                print(trial.report(), flush=True)
            else:
                print("ok   fault %d: %s (%s)" % (trial.index, trial.fault, "; ".join(trial.notes)), flush=True)
    took = time.monotonic() - start
    print("fault-campaign: seed=%d %d faults (%s) in %.0f s: %d failed" %
          (seed, args.faults, " ".join("%s=%d" % kv for kv in sorted(counts.items())), took, failed), flush=True)
    if failed == 0 and not args.keep:
        subprocess.run(["rm", "-rf", tmp])
    else:
        print("fault-campaign: logs in %s" % tmp)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
