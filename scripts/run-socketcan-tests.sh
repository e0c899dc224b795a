#!/usr/bin/env bash
# Runs the SocketCAN tests (ctest label `socketcan`) inside a user-mode Linux
# kernel (Debian's user-mode-linux), because the host kernel may have no AF_CAN.
# The guest boots with the host's / as its root (hostfs), loads can, can-raw,
# can-dev and vcan, creates vcan0 (and brings lo up), cds into BUILD_DIR and
# runs the command there with can-utils on PATH. The command's exit status is
# written to a file on the host and becomes this script's exit status; a
# missing status (panic, crash, timeout) is a failure. docs/can-bus.md explains the setup.
#
# Usage: scripts/run-socketcan-tests.sh [--timeout SECONDS] [--mem SIZE] BUILD_DIR [-- COMMAND...]
#   default COMMAND: ctest -L socketcan --output-on-failure
#   environment: P3AT_UML_TIMEOUT (seconds, default 240), P3AT_UML_MEM (default 2G),
#                P3AT_UML_KEEP=1 keeps the scratch folder, LINUX_UML (the kernel binary).
# Exit status: the guest command's; 2 for bad usage or a missing prerequisite;
# 3 when the guest reported no status; 4 when the guest could not set up vcan0.
set -euo pipefail

die() { echo "run-socketcan-tests: $*" >&2; exit 2; }

timeout_s="${P3AT_UML_TIMEOUT:-240}"
mem="${P3AT_UML_MEM:-2G}"
build_dir=""
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
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
if [ $# -gt 0 ]; then cmd=("$@"); else cmd=(ctest -L socketcan --output-on-failure); fi
# AddressSanitizer's shadow memory needs a 47-bit address space; UML gives a
# process 39 bits (its stack sits below 0x7fc0000000), so ASan aborts at start.
if grep -Eq '^P3AT_(SANITIZE|FUZZ):BOOL=(ON|1|TRUE)' "$build_dir/CMakeCache.txt"; then
  die "'$build_dir' is built with AddressSanitizer, which cannot run inside user-mode Linux (its shadow memory needs a 47-bit address space, UML processes have 39 bits); use a build without P3AT_SANITIZE"
fi

# ---- prerequisites (Debian: user-mode-linux, busybox-static, can-utils, a C compiler)
uml="${LINUX_UML:-$(command -v linux.uml || true)}"
[ -n "$uml" ] && [ -x "$uml" ] || die "linux.uml not found (Debian package user-mode-linux)"
modules_root=/usr/lib/uml/modules
moddir="$(find "$modules_root" -mindepth 1 -maxdepth 1 -type d 2>/dev/null | head -n 1)"
[ -n "$moddir" ] || die "no kernel modules under $modules_root (package user-mode-linux)"
for m in net/can/can.ko net/can/can-raw.ko drivers/net/can/dev/can-dev.ko drivers/net/can/vcan.ko; do
  [ -f "$moddir/kernel/$m" ] || die "module $moddir/kernel/$m is missing"
done
busybox=""
for b in /bin/busybox /usr/bin/busybox; do
  if [ -x "$b" ] && ! ldd "$b" >/dev/null 2>&1; then busybox="$b"; break; fi
done
[ -n "$busybox" ] || die "no static busybox (Debian package busybox-static)"
for tool in candump cansend; do command -v "$tool" >/dev/null || die "$tool not found (Debian package can-utils)"; done
cc="${CC:-cc}"
command -v "$cc" >/dev/null || die "no C compiler ('$cc') to build the ptrace shim"

work="$(mktemp -d /tmp/p3at-uml.XXXXXX)"
uml_pid=""
watchdog_pid=""
cleanup() {
  [ -n "$watchdog_pid" ] && kill "$watchdog_pid" 2>/dev/null || true
  [ -n "$uml_pid" ] && kill -KILL -- "-$uml_pid" 2>/dev/null || true
  if [ "${P3AT_UML_KEEP:-0}" = 1 ]; then echo "run-socketcan-tests: kept $work" >&2; else rm -rf "$work"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# ---- the ptrace shim
# UML (6.1) saves a guest process's FPU state with PTRACE_GETREGSET/SETREGSET
# NT_X86_XSTATE using its own, smaller XSAVE buffer. Host kernels demand the
# full XSAVE size on SETREGSET, which on CPUs with AMX (~11 KB) UML's buffer is
# not, so the first context switch fails ("ptrace set fp regs failed, errno = 14")
# and the kernel panics. Refusing NT_X86_XSTATE makes UML fall back to
# PTRACE_GETFPREGS/SETFPREGS (x87 + SSE state), which works everywhere; the
# guest's glibc is then told not to use AVX (GLIBC_TUNABLES below), because the
# fallback does not preserve AVX registers. Our own code is built for baseline
# x86-64 (SSE2) and is unaffected.
cat >"$work/xstate_shim.c" <<'EOF'
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdarg.h>
#include <sys/ptrace.h>
#include <sys/types.h>

#define NT_X86_XSTATE 0x202

long ptrace(enum __ptrace_request request, ...) {
  va_list ap;
  va_start(ap, request);
  pid_t pid = va_arg(ap, pid_t);
  void* addr = va_arg(ap, void*);
  void* data = va_arg(ap, void*);
  va_end(ap);
  if ((request == PTRACE_GETREGSET || request == PTRACE_SETREGSET) && (unsigned long)addr == NT_X86_XSTATE) {
    errno = EIO;
    return -1;
  }
  static long (*real)(int, pid_t, void*, void*);
  if (!real) real = (long (*)(int, pid_t, void*, void*))dlsym(RTLD_NEXT, "ptrace");
  return real((int)request, pid, addr, data);
}
EOF
"$cc" -O2 -shared -fPIC -o "$work/xstate_shim.so" "$work/xstate_shim.c" -ldl \
  || die "could not build the ptrace shim with $cc"
tunables="glibc.cpu.hwcaps=-AVX,-AVX2,-AVX512F,-AVX512VL,-AVX512BW,-AVX512DQ,-AVX512CD,-AVX_Fast_Unaligned_Load"

# ---- the guest's init
q() { printf '%q' "$1"; }
{
  echo "#!$busybox sh"
  echo "# generated by scripts/run-socketcan-tests.sh"
  echo "B=$busybox"
  echo "export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=$(q "$work") TMPDIR=/tmp LANG=C.UTF-8"
  echo "export P3AT_REQUIRE_SOCKETCAN=1 P3AT_IN_UML=1"
  for v in ASAN_OPTIONS UBSAN_OPTIONS LSAN_OPTIONS CTEST_OUTPUT_ON_FAILURE CTEST_PARALLEL_LEVEL; do
    if [ -n "${!v:-}" ]; then echo "export $v=$(q "${!v}")"; fi
  done
  cat <<EOF
status=$(q "$work/status")
setup_failed() { echo "[uml] setup failed: \$*"; echo 4 > "\$status"; \$B poweroff -f; }
\$B mount -t proc proc /proc || setup_failed "mount /proc"
\$B mount -t sysfs sysfs /sys || setup_failed "mount /sys"
\$B mkdir -p /dev/shm /dev/pts
\$B mount -t tmpfs tmpfs /dev/shm || setup_failed "mount /dev/shm"
\$B mount -t devpts devpts /dev/pts || setup_failed "mount /dev/pts"
for m in net/can/can.ko net/can/can-raw.ko drivers/net/can/dev/can-dev.ko drivers/net/can/vcan.ko; do
  \$B insmod $(q "$moddir")/kernel/\$m || setup_failed "insmod \$m"
done
\$B ip link set lo up || setup_failed "lo up"
\$B ip link add dev vcan0 type vcan || setup_failed "ip link add vcan0"
\$B ip link set vcan0 up || setup_failed "vcan0 up"
cd $(q "$build_dir") || setup_failed "cd $(q "$build_dir")"
echo "[uml] kernel=\$(\$B uname -r) vcan0=up modules=can,can-raw,can-dev,vcan"
echo "[uml] running: $(printf '%q ' "${cmd[@]}")"
start=\$(\$B date +%s)
$(printf '%q ' "${cmd[@]}")
rc=\$?
echo "[uml] exit_status=\$rc run_s=\$((\$(\$B date +%s) - start))"
echo "\$rc" > "\$status"
\$B sync
\$B poweroff -f
EOF
} >"$work/init"
chmod +x "$work/init"

# ---- boot
mkdir -p "$work/uml"
shm_kb="$(df -Pk /dev/shm 2>/dev/null | awk 'NR==2 {print $4}')"
mem_kb=$(( ${mem%[MG]} * 1024 ))
if [ "${mem: -1}" = G ]; then mem_kb=$(( mem_kb * 1024 )); fi
# UML backs the guest's memory with a file in TMPDIR, else /dev/shm; a small /dev/shm (containers) is not enough.
if [ -z "$shm_kb" ] || [ "$shm_kb" -lt "$mem_kb" ]; then export TMPDIR="$work/uml"; fi
echo "run-socketcan-tests: booting $uml (modules $(basename "$moddir")) with $build_dir, timeout ${timeout_s}s"
t0=$(date +%s.%N)
# setsid: the kernel and its helper processes form one process group the watchdog can end.
LD_PRELOAD="$work/xstate_shim.so" setsid "$uml" mem="$mem" root=/dev/root rootfstype=hostfs rootflags=/ rw \
  uml_dir="$work/uml" init="$work/init" con=null con0=null,fd:1 quiet "GLIBC_TUNABLES=$tunables" </dev/null &
uml_pid=$!
# The watchdog's sleep holds no output descriptor, so a pipe reading our output
# ends when we do; on our TERM it ends its sleep.
( trap 'kill "$sleep_pid" 2>/dev/null; exit 0' TERM
  sleep "$timeout_s" >/dev/null 2>&1 </dev/null & sleep_pid=$!
  wait "$sleep_pid" || exit 0
  echo "run-socketcan-tests: timeout after ${timeout_s}s, stopping the guest" >&2
  kill -TERM -- "-$uml_pid" 2>/dev/null; sleep 5 >/dev/null 2>&1 </dev/null; kill -KILL -- "-$uml_pid" 2>/dev/null ) &
watchdog_pid=$!
wait "$uml_pid" || true
uml_pid=""
kill "$watchdog_pid" 2>/dev/null || true
wait "$watchdog_pid" 2>/dev/null || true
watchdog_pid=""
elapsed="$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')"

if [ ! -s "$work/status" ]; then
  echo "run-socketcan-tests: FAILED: the guest reported no exit status (kernel panic, crash or timeout) after ${elapsed}s" >&2
  exit 3
fi
status="$(tr -dc '0-9' <"$work/status")"
[ -n "$status" ] || status=3
if [ "$status" = 0 ]; then
  echo "run-socketcan-tests: passed in the guest (boot, run and shutdown ${elapsed}s)"
else
  echo "run-socketcan-tests: FAILED in the guest with status $status (${elapsed}s)" >&2
fi
exit "$status"
