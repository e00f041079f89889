// springlab_worker_seccomp: writes the seccomp filter of the grader's workers to standard
// output, as the BPF program bubblewrap loads (`bwrap --seccomp FD`) just before it starts the
// worker. The grader runs it once per session (tools/springlab_grader/judged_run.py).
//
// Bubblewrap's namespaces already hide the grading tree, the network and other processes;
// this filter takes away what exercise code never needs and an escape would: new processes
// (threads stay: OpenMP), reading or tracing other processes' memory, the kernel's
// attack surface (eBPF, perf, io_uring, keyrings, user faults, modules), and new namespaces
// or mounts. A denied call fails with EPERM (clone3 with ENOSYS, so that the C library falls
// back to clone, whose flags the filter can read).
#include <seccomp.h>

#include <cerrno>
#include <cstdio>
#include <sched.h>
#include <unistd.h>

namespace {

// Each syscall the workers may not make, by name (libseccomp resolves it for this machine's
// architecture; a name the kernel headers lack is skipped).
constexpr const char* kDenied[] = {
    "fork", "vfork", "ptrace", "process_vm_readv", "process_vm_writev", "kcmp", "pidfd_open",
    "pidfd_getfd", "bpf", "perf_event_open", "userfaultfd", "io_uring_setup", "io_uring_enter",
    "io_uring_register", "keyctl", "add_key", "request_key", "init_module", "finit_module",
    "delete_module", "kexec_load", "kexec_file_load", "mount", "umount2", "pivot_root", "chroot",
    "unshare", "setns", "personality", "socket", "socketpair", "acct", "swapon", "swapoff",
    "reboot", "sethostname", "setdomainname", "iopl", "ioperm", "open_by_handle_at",
    "name_to_handle_at", "move_mount", "open_tree", "fsopen", "fsmount", "fsconfig", "fspick",
    "quotactl", "syslog", "lookup_dcookie", "nfsservctl", "uselib", "vhangup",
};

}  // namespace

int main() {
  scmp_filter_ctx filter = seccomp_init(SCMP_ACT_ALLOW);
  if (filter == nullptr) {
    std::fprintf(stderr, "springlab_worker_seccomp: seccomp_init failed\n");
    return 1;
  }
  int failed = 0;
  for (const char* name : kDenied) {
    const int nr = seccomp_syscall_resolve_name(name);
    if (nr == __NR_SCMP_ERROR) continue;
    failed |= seccomp_rule_add(filter, SCMP_ACT_ERRNO(EPERM), nr, 0);
  }
  // clone: threads only (CLONE_THREAD set); a new process fails. clone3 hides its flags in
  // memory the filter cannot read, so it answers "not implemented" and the C library uses clone.
  failed |= seccomp_rule_add(filter, SCMP_ACT_ERRNO(EPERM), SCMP_SYS(clone), 1,
                             SCMP_A0(SCMP_CMP_MASKED_EQ, CLONE_THREAD, 0));
  failed |= seccomp_rule_add(filter, SCMP_ACT_ERRNO(ENOSYS), SCMP_SYS(clone3), 0);
  if (failed != 0 || seccomp_export_bpf(filter, STDOUT_FILENO) != 0) {
    std::fprintf(stderr, "springlab_worker_seccomp: cannot build the filter\n");
    seccomp_release(filter);
    return 1;
  }
  seccomp_release(filter);
  return 0;
}
