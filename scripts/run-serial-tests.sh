#!/usr/bin/env bash
# Runs the serial tests (ctest label `serial`) inside a QEMU virtual machine
# whose /dev/ttyS0 is an emulated 16550 UART served by the Linux 8250 driver,
# because libserialport cannot open pseudo-terminals (docs/hal.md, "Serial rig").
# The guest boots a Debian kernel (downloaded with apt-get, extracted, never
# installed; cached), mounts the host's / read-only over virtio-9p (so the build
# tree, shared libraries and ctest are the host's), cds into BUILD_DIR and runs
# the command there. ttyS0's far end is QEMU's TCP character device, connected
# through QEMU's user-mode network to guest port 8101, where the tests start
# p3at_sim (or a peer of their own): guest tty -> 8250 driver -> emulated UART ->
# TCP -> guest. The command's exit status is written to a scratch folder shared
# read-write with the guest and becomes this script's; a missing status (panic,
# crash, timeout) is a failure.
#
# Usage: scripts/run-serial-tests.sh [--timeout SECONDS] [--mem SIZE] BUILD_DIR [-- COMMAND...]
#   default COMMAND: ctest -L serial --output-on-failure
#   environment: P3AT_QEMU_TIMEOUT (seconds, default 420), P3AT_QEMU_MEM (default 2G),
#                P3AT_QEMU_KEEP=1 keeps the scratch folder, P3AT_QEMU_CACHE (kernel cache,
#                default ~/.cache/p3at-serial-rig), P3AT_QEMU_KERNEL_PKG (Debian package,
#                default the one linux-image-amd64 depends on).
# Exit status: the guest command's; 2 for bad usage or a missing prerequisite;
# 3 when the guest reported no status; 4 when the guest could not set itself up.
set -euo pipefail

die() { echo "run-serial-tests: $*" >&2; exit 2; }
say() { echo "run-serial-tests: $*"; }

timeout_s="${P3AT_QEMU_TIMEOUT:-420}"
mem="${P3AT_QEMU_MEM:-2G}"
build_dir=""
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    --timeout) [ $# -ge 2 ] || die "--timeout needs a value"; timeout_s="$2"; shift 2 ;;
    --mem) [ $# -ge 2 ] || die "--mem needs a value"; mem="$2"; shift 2 ;;
    --) shift; break ;;
    -*) die "unknown option '$1' (see --help)" ;;
    *) [ -z "$build_dir" ] || die "more than one BUILD_DIR ('$build_dir', '$1')"; build_dir="$1"; shift ;;
  esac
done
[ -n "$build_dir" ] || die "usage: $0 [--timeout SECONDS] [--mem SIZE] BUILD_DIR [-- COMMAND...]"
[[ "$timeout_s" =~ ^[0-9]+$ ]] && [ "$timeout_s" -gt 0 ] || die "--timeout must be a positive number of seconds"
[[ "$mem" =~ ^[0-9]+[MG]$ ]] || die "--mem must look like 512M or 2G"
[ -d "$build_dir" ] || die "no build directory '$build_dir'"
build_dir="$(cd "$build_dir" && pwd -P)"
[ -f "$build_dir/CTestTestfile.cmake" ] || die "'$build_dir' is not a CMake build tree (no CTestTestfile.cmake)"
case "$build_dir/" in
  /tmp/*|/run/*|/var/tmp/*|/dev/*|/proc/*|/sys/*)
    die "'$build_dir' is under a folder the guest replaces with its own (tmpfs, proc, sys); build elsewhere" ;;
esac
if [ $# -gt 0 ]; then cmd=("$@"); else cmd=(ctest -L serial --output-on-failure); fi
# The guest sees the build tree read-only; ctest writes its logs under Testing/,
# which the guest covers with a tmpfs (the folder must exist to mount on).
mkdir -p "$build_dir/Testing"

# ---- prerequisites (Debian: qemu-system-x86, busybox-static, apt, dpkg)
qemu="$(command -v qemu-system-x86_64 || true)"
[ -n "$qemu" ] || die "qemu-system-x86_64 not found (Debian package qemu-system-x86)"
busybox=""
for b in /bin/busybox /usr/bin/busybox; do
  if [ -x "$b" ] && ! ldd "$b" >/dev/null 2>&1; then busybox="$b"; break; fi
done
[ -n "$busybox" ] || die "no static busybox (Debian package busybox-static)"
for tool in dpkg-deb gzip python3 flock; do command -v "$tool" >/dev/null || die "$tool not found"; done

# ---- the guest kernel: a Debian linux-image package, extracted (never installed) and cached
# Modules the guest needs, by file name: virtio-pci, 9p over virtio, virtio-net.
# Their own dependencies are read from each module's depends= field.
wanted_modules=(virtio_pci 9pnet_virtio 9p virtio_net)
cache="${P3AT_QEMU_CACHE:-${XDG_CACHE_HOME:-${HOME:-/root}/.cache}/p3at-serial-rig}"
mkdir -p "$cache"
pkg="${P3AT_QEMU_KERNEL_PKG:-}"
if [ -z "$pkg" ]; then
  pkg="$(apt-cache depends linux-image-amd64 2>/dev/null | awk '/Depends: linux-image-[0-9]/ {print $2; exit}')"
  # Offline or no package lists: fall back to the newest kernel already in the cache.
  if [ -z "$pkg" ]; then pkg="$(ls -1 "$cache" 2>/dev/null | grep '^linux-image-' | sort -V | tail -n 1 || true)"; fi
fi
[ -n "$pkg" ] || die "cannot tell which Debian kernel to use (apt-cache depends linux-image-amd64 found none; run apt-get update)"
kdir="$cache/$pkg"
# One fetch at a time per cache (two runs may start together on a shared machine).
exec 9>"$cache/.lock"
flock 9
if [ ! -f "$kdir/ready" ]; then
  say "fetching and extracting $pkg into $kdir (once per kernel version)"
  rm -rf "$kdir" "$kdir.part"
  mkdir -p "$kdir.part"
  (cd "$kdir.part" && apt-get download -o APT::Sandbox::User=root "$pkg" >/dev/null) \
    || die "apt-get download $pkg failed"
  deb="$(ls "$kdir.part"/*.deb)"
  dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$kdir.part" --wildcards './boot/vmlinuz-*' './lib/modules/*/kernel/drivers/virtio/*' \
      './lib/modules/*/kernel/net/9p/*' './lib/modules/*/kernel/fs/9p/*' './lib/modules/*/kernel/fs/netfs/*' \
      './lib/modules/*/kernel/fs/fscache/*' './lib/modules/*/kernel/drivers/net/virtio_net.ko' \
      './lib/modules/*/kernel/drivers/net/net_failover.ko' './lib/modules/*/kernel/net/core/failover.ko' \
    || die "could not extract the kernel and modules from $deb"
  rm -f "$deb"
  date -u +%FT%TZ >"$kdir.part/ready"
  mv "$kdir.part" "$kdir"
fi
flock -u 9
exec 9>&-
vmlinuz="$(ls "$kdir"/boot/vmlinuz-* 2>/dev/null | head -n 1)"
[ -n "$vmlinuz" ] || die "no vmlinuz in $kdir (remove it to fetch again)"
modroot="$(ls -d "$kdir"/lib/modules/*/kernel | head -n 1)"

# Load order: each module after what its depends= field names.
declare -A module_path=()
while IFS= read -r f; do module_path["$(basename "$f" .ko)"]="$f"; done < <(find "$modroot" -name '*.ko')
declare -A seen=()
load_order=()
add_module() {
  local m="$1" dep deps
  [ -n "${seen[$m]:-}" ] && return 0
  seen[$m]=1
  [ -n "${module_path[$m]:-}" ] || die "module $m is not in $pkg (extracted into $modroot)"
  deps="$(grep -a -o 'depends=[A-Za-z0-9_,-]*' "${module_path[$m]}" | head -n 1 | cut -d= -f2 | tr ',-' ' _')"
  for dep in $deps; do add_module "$dep"; done
  load_order+=("$m")
}
for m in "${wanted_modules[@]}"; do add_module "$m"; done

work="$(mktemp -d /tmp/p3at-qemu.XXXXXX)"
qemu_pid=""
watchdog_pid=""
cleanup() {
  [ -n "$watchdog_pid" ] && kill "$watchdog_pid" 2>/dev/null || true
  [ -n "$qemu_pid" ] && kill -KILL "$qemu_pid" 2>/dev/null || true
  if [ "${P3AT_QEMU_KEEP:-0}" = 1 ]; then echo "run-serial-tests: kept $work" >&2; else rm -rf "$work"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# The guest port the serial line's far end reaches (tests listen there), and a
# free host port for QEMU's forward to it.
guest_port=8101
host_port="$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"

# ---- stage 1: the initramfs (busybox, the modules, an init that mounts the host)
q() { printf '%q' "$1"; }
share="$work/share"   # read-write with the guest: stage 2 script, status, HOME
mkdir -p "$work/initramfs/bin" "$work/initramfs/modules" "$share/home"
for d in proc sys dev newroot; do mkdir -p "$work/initramfs/$d"; done
cp "$busybox" "$work/initramfs/bin/busybox"
for m in "${load_order[@]}"; do cp "${module_path[$m]}" "$work/initramfs/modules/$m.ko"; done
cat >"$work/initramfs/init" <<EOF
#!/bin/busybox sh
# generated by scripts/run-serial-tests.sh: stage 1, inside the initramfs
B=/bin/busybox
fail() { echo "[qemu] setup failed: \$*"; \$B poweroff -f; }
\$B mount -t proc proc /proc && \$B mount -t sysfs sysfs /sys && \$B mount -t devtmpfs devtmpfs /dev || fail "proc/sys/dev"
for m in ${load_order[*]}; do \$B insmod /modules/\$m.ko || fail "insmod \$m"; done
\$B mount -t 9p -o trans=virtio,version=9p2000.L,ro,msize=262144,cache=loose hostroot /newroot || fail "mount the host's / over 9p"
\$B mount -t tmpfs -o mode=1777 tmpfs /newroot/tmp || fail "tmpfs /tmp"
\$B mkdir -p /newroot$(q "$share")
\$B mount -t 9p -o trans=virtio,version=9p2000.L,rw,msize=262144 share /newroot$(q "$share") || fail "mount the scratch share"
for d in proc sys dev; do \$B mount --move /\$d /newroot/\$d || fail "move /\$d"; done
exec \$B switch_root /newroot $(q "$share/stage2")
EOF
chmod +x "$work/initramfs/init"
(cd "$work/initramfs" && find . | "$busybox" cpio -o -H newc 2>/dev/null | gzip -1) >"$work/initramfs.cpio.gz"

# ---- stage 2: runs as PID 1 with the host's / (read-only) as root
{
  echo "#!$busybox sh"
  echo "# generated by scripts/run-serial-tests.sh: stage 2, the host's / as root"
  echo "B=$busybox"
  echo "export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=$(q "$share/home") TMPDIR=/tmp LANG=C.UTF-8"
  echo "export P3AT_SERIAL_RIG=1 P3AT_REQUIRE_SERIAL=1 P3AT_SERIAL_DEVICE=/dev/ttyS0 P3AT_SERIAL_PEER_PORT=$guest_port"
  for v in CTEST_OUTPUT_ON_FAILURE CTEST_PARALLEL_LEVEL; do
    if [ -n "${!v:-}" ]; then echo "export $v=$(q "${!v}")"; fi
  done
  cat <<EOF
status=$(q "$share/status")
setup_failed() { echo "[qemu] setup failed: \$*"; echo 4 > "\$status"; \$B sync; \$B poweroff -f; }
\$B mkdir -p /dev/pts /dev/shm
\$B mount -t devpts devpts /dev/pts || setup_failed "mount /dev/pts"
\$B mount -t tmpfs tmpfs /dev/shm || setup_failed "mount /dev/shm"
for d in /run /var/tmp; do \$B mount -t tmpfs tmpfs \$d || setup_failed "tmpfs \$d"; done
\$B ip link set lo up || setup_failed "lo up"
# LCM's team link: UDP multicast on the loopback (ttl=0), as on the host.
\$B ip link set lo multicast on && \$B ip route add 224.0.0.0/4 dev lo || setup_failed "multicast route on lo"
# QEMU's user-mode network: the guest is 10.0.2.15; only the forward to port $guest_port is used.
\$B ip addr add 10.0.2.15/24 dev eth0 && \$B ip link set eth0 up || setup_failed "eth0 up"
[ -e /sys/class/tty/ttyS0 ] || setup_failed "no /sys/class/tty/ttyS0"
\$B mount -t tmpfs tmpfs $(q "$build_dir/Testing") || setup_failed "tmpfs on the build tree's Testing/"
cd $(q "$build_dir") || setup_failed "cd $(q "$build_dir")"
echo "[qemu] kernel=\$(\$B uname -r) boot_s=\$(\$B cut -d' ' -f1 /proc/uptime) ttyS0=\$(\$B grep '^0:' /proc/tty/driver/serial | \$B cut -d' ' -f2)"
echo "[qemu] running: $(printf '%q ' "${cmd[@]}")"
start=\$(\$B cut -d' ' -f1 /proc/uptime)
$(printf '%q ' "${cmd[@]}")
rc=\$?
echo "[qemu] exit_status=\$rc run_s=\$(\$B awk -v a=\$start -v b=\$(\$B cut -d' ' -f1 /proc/uptime) 'BEGIN { printf "%.1f", b - a }')"
echo "\$rc" > "\$status"
\$B sync
\$B poweroff -f
EOF
} >"$share/stage2"
chmod +x "$share/stage2"

# ---- boot. Always TCG: KVM on these machines aborts (-cpu host: "failed to set
# MSR 0x10a") or hangs without output (docs/hal.md).
mem_mb=${mem%[MG]}
if [ "${mem: -1}" = G ]; then mem_mb=$(( mem_mb * 1024 )); fi
say "booting $(basename "$vmlinuz") under QEMU (TCG) with $build_dir; ttyS0 <-> tcp 127.0.0.1:$host_port <-> guest :$guest_port; timeout ${timeout_s}s"
say "(QEMU's 'Unable to connect character device robot' at start is expected: nothing listens in the guest yet; it retries every second)"
t0=$(date +%s.%N)
"$qemu" -accel tcg -cpu max -smp 2 -m "$mem_mb" -nodefaults -no-user-config -display none -no-reboot \
  -kernel "$vmlinuz" -initrd "$work/initramfs.cpio.gz" -append "console=ttyS1 panic=-1 quiet" \
  -chardev socket,id=robot,host=127.0.0.1,port="$host_port",reconnect=1 -serial chardev:robot \
  -chardev stdio,id=console,signal=off -serial chardev:console \
  -netdev user,id=net0,restrict=on,hostfwd=tcp:127.0.0.1:"$host_port"-10.0.2.15:"$guest_port" \
  -device virtio-net-pci,netdev=net0 \
  -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
  -virtfs local,path="$share",mount_tag=share,security_model=none,multidevs=remap \
  </dev/null &
qemu_pid=$!
( trap 'kill "$sleep_pid" 2>/dev/null; exit 0' TERM
  sleep "$timeout_s" >/dev/null 2>&1 </dev/null & sleep_pid=$!
  wait "$sleep_pid" || exit 0
  echo "run-serial-tests: timeout after ${timeout_s}s, stopping the guest" >&2
  kill -TERM "$qemu_pid" 2>/dev/null; sleep 5 >/dev/null 2>&1 </dev/null; kill -KILL "$qemu_pid" 2>/dev/null ) &
watchdog_pid=$!
wait "$qemu_pid" || true
qemu_pid=""
kill "$watchdog_pid" 2>/dev/null || true
wait "$watchdog_pid" 2>/dev/null || true
watchdog_pid=""
elapsed="$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')"

if [ ! -s "$share/status" ]; then
  echo "run-serial-tests: FAILED: the guest reported no exit status (kernel panic, crash or timeout) after ${elapsed}s" >&2
  exit 3
fi
status="$(tr -dc '0-9' <"$share/status")"
[ -n "$status" ] || status=3
if [ "$status" = 0 ]; then
  say "passed in the guest (boot, run and shutdown ${elapsed}s)"
else
  echo "run-serial-tests: FAILED in the guest with status $status (${elapsed}s)" >&2
fi
exit "$status"
