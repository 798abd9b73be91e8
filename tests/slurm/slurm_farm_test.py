#!/usr/bin/python3
"""slurm_farm_test.py BUILD_DIR SOURCE_DIR

One frame of a caustic scene rendered on a Slurm cluster brought up on localhost: MUNGE, slurmctld and
slurmd with a minimal slurm.conf written here (one node, 2 CPUs, no cgroups, no accounting), the frame
submitted by packaging/slurm/nimbus-slurm-submit as a 4-task job array plus the dependent merge job. The
merged image is then compared with single-machine renders of the same 32 iterations: its error (MAPE)
against the same-seed render and against another seed is at the level of two independent renders (the
ratios are printed), its mean is within 5 standard errors of the other seed's (the standard error from the
spread of 8 more single renders' means), and the caustics element and LightMix layers are there. If the
daemons cannot start, the test says why and fails.
"""
import json
import math
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

TASKS, ITERATIONS, SPREAD_RENDERS = 4, 32, 8
NODE = "nimbusnode"


class Failure(Exception):
    pass


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def tail(path, lines=30):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError as e:
        return f"({e})"


class Cluster:
    """MUNGE, slurmctld and slurmd for one node, everything under `work`."""

    def __init__(self, work):
        self.work = work
        self.procs = []
        self.env = dict(os.environ, SLURM_CONF=os.path.join(work, "slurm.conf"))

    def start(self):
        for tool in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo", "scontrol"):
            if not shutil.which(tool):
                raise Failure(f"{tool} is not installed (bash packaging/setup.sh installs slurm-wlm and munge)")
        if os.geteuid() != 0:
            raise Failure("slurmd must run as root to start jobs as their user; run the test as root")
        w = self.work
        for d in ("munge", "state", "spool"):
            os.makedirs(os.path.join(w, d), exist_ok=True)
        key = os.path.join(w, "munge", "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        os.chmod(os.path.join(w, "munge"), 0o700)
        self.socket = os.path.join(w, "munge", "munge.socket")
        munged = subprocess.run(
            ["munged", "--force", "--key-file", key, "--socket", self.socket,
             "--pid-file", os.path.join(w, "munge", "munged.pid"),
             "--log-file", os.path.join(w, "munge", "munged.log"),
             "--seed-file", os.path.join(w, "munge", "munged.seed")],
            capture_output=True, text=True)
        if munged.returncode != 0:
            raise Failure(f"munged did not start: {munged.stderr.strip()}")
        host = socket.gethostname().split(".")[0]
        conf = f"""ClusterName=nimbus-test
SlurmctldHost={host}(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
AuthType=auth/munge
AuthInfo=socket={self.socket}
CredType=cred/munge
StateSaveLocation={w}/state
SlurmdSpoolDir={w}/spool
SlurmctldPidFile={w}/slurmctld.pid
SlurmdPidFile={w}/slurmd.pid
SlurmctldLogFile={w}/slurmctld.log
SlurmdLogFile={w}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=600
NodeName={NODE} NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=farm Nodes={NODE} Default=YES MaxTime=INFINITE State=UP
"""
        with open(self.env["SLURM_CONF"], "w") as f:
            f.write(conf)
        self.procs.append(subprocess.Popen(["slurmctld", "-D", "-i"], env=self.env,
                                           stdout=subprocess.DEVNULL, stderr=open(f"{w}/slurmctld.err", "w")))
        self.procs.append(subprocess.Popen(["slurmd", "-D", "-N", NODE], env=self.env,
                                           stdout=subprocess.DEVNULL, stderr=open(f"{w}/slurmd.err", "w")))
        deadline = time.time() + 60
        state = ""
        while time.time() < deadline:
            for p, name in zip(self.procs, ("slurmctld", "slurmd")):
                if p.poll() is not None:
                    raise Failure(f"{name} exited with {p.returncode}: {tail(f'{w}/{name}.err')}"
                                  f"{tail(f'{w}/{name}.log')}")
            r = subprocess.run(["sinfo", "-h", "-N", "-o", "%T"], env=self.env, capture_output=True, text=True)
            state = r.stdout.strip() or r.stderr.strip()
            if state == "idle":
                return
            time.sleep(0.5)
        raise Failure(f"the node did not become idle within 60 s (sinfo: {state!r}); slurmctld log:\n"
                      f"{tail(f'{w}/slurmctld.log')}\nslurmd log:\n{tail(f'{w}/slurmd.log')}")

    def job_state(self, job):
        r = subprocess.run(["scontrol", "-o", "show", "job", job], env=self.env, capture_output=True, text=True)
        states = [f.split("=", 1)[1] for line in r.stdout.splitlines() for f in line.split()
                  if f.startswith("JobState=")]
        return states

    def stop(self):
        subprocess.run(["scontrol", "shutdown"], env=self.env, capture_output=True)
        for p in self.procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
        pid_file = os.path.join(self.work, "munge", "munged.pid")
        if os.path.exists(pid_file):
            try:
                os.kill(int(open(pid_file).read().strip()), 15)
            except (OSError, ValueError):
                pass


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise Failure(f"{' '.join(cmd)} exited with {r.returncode}: {r.stderr.strip()}")
    return r.stdout


def mean_luminance(path):
    """The image's mean luminance, from oiiotool's per-channel averages of beauty."""
    out = run(["oiiotool", path, "--ch", "R,G,B", "--printstats"])
    for line in out.splitlines():
        if "Stats Avg:" in line:
            r, g, b = (float(v) for v in line.split(":", 1)[1].split()[:3])
            return 0.2126 * r + 0.7152 * g + 0.0722 * b
    raise Failure(f"no averages from oiiotool for {path}: {out}")


def main(build, source):
    nimbus = os.path.join(build, "bin", "nimbus")
    submit = os.path.join(source, "packaging", "slurm", "nimbus-slurm-submit")
    work = tempfile.mkdtemp(prefix="slurm.", dir=os.path.join(build, "tests"))
    os.chmod(work, 0o755)
    scene = os.path.join(source, "tests", "e2e", "scenes", "split_sphere.yaml")
    cluster = Cluster(work)
    ok = False
    try:
        cluster.start()
        merged = os.path.join(work, "farm", "merged.exr")
        t0 = time.time()
        out = run([submit, scene, "-o", merged, "--tasks", str(TASKS), "--cpus", "1", "--nimbus", nimbus,
                   "--", "--iterations", str(ITERATIONS)], env=cluster.env)
        print(out.strip())
        array_id, merge_id = open(os.path.join(work, "farm", "merged.parts", "merged.jobs")).read().split()
        deadline = time.time() + 600
        while time.time() < deadline:
            states = cluster.job_state(merge_id)
            if states and states[0] not in ("PENDING", "RUNNING", "CONFIGURING", "COMPLETING"):
                break
            time.sleep(1)
        farm_seconds = time.time() - t0
        logs = os.path.join(work, "farm", "merged.parts")
        if cluster.job_state(merge_id)[:1] != ["COMPLETED"]:
            raise Failure(f"the merge job ended {cluster.job_state(merge_id)}; tasks "
                          f"{cluster.job_state(array_id)}; merge log: {tail(os.path.join(logs, 'merged.merge.log'))}")
        if set(cluster.job_state(array_id)) != {"COMPLETED"}:
            raise Failure(f"array tasks ended {cluster.job_state(array_id)}")
        print(f"array of {TASKS} tasks and merge: {farm_seconds:.1f} s")

        t0 = time.time()
        single = os.path.join(work, "single.exr")
        run([nimbus, "render", scene, "-q", "--iterations", str(ITERATIONS), "--threads", "2", "-o", single])
        print(f"single render of {ITERATIONS} iterations: {time.time() - t0:.1f} s")
        other = os.path.join(work, "other.exr")
        run([nimbus, "render", scene, "-q", "--iterations", str(ITERATIONS), "--threads", "2", "--seed", "2",
             "-o", other])

        # The levels are compared by MAPE: a few pixels at the caustic's focus carry a third of a render's
        # relMSE, which makes ratios of relMSE swing by more than the bounds below between seeds.
        def error(test, ref, element="beauty", metric="mape"):
            return json.loads(run([nimbus, "compare", test, ref, "--json", "--element", element]))[metric]

        e_merged_single, e_other_single = error(merged, single), error(other, single)
        e_merged_other, e_single_other = error(merged, other), error(single, other)
        print(f"MAPE: merged/single {e_merged_single:.5f}, other seed/single {e_other_single:.5f}; "
              f"merged/other seed {e_merged_other:.5f}, single/other seed {e_single_other:.5f} (relMSE "
              f"{error(merged, other, metric='relmse_luminance'):.5f} and "
              f"{error(single, other, metric='relmse_luminance'):.5f})")
        if not e_merged_single < 1.3 * e_other_single:
            raise Failure("the merged image is farther from the single render than an independent render is")
        if not e_single_other / 1.3 < e_merged_other < 1.3 * e_single_other:
            raise Failure("the merged image's error is not at the level of a single render's")
        for element in ("caustics", "lightmix.key", "lightmix.fill"):
            error(merged, single, element)  # fails when the layer is missing from either
        # The spread of a single render's mean, from independent renders of the same length.
        means = []
        for seed in range(3, 3 + SPREAD_RENDERS):
            spread = os.path.join(work, f"spread{seed}.exr")
            run([nimbus, "render", scene, "-q", "--iterations", str(ITERATIONS), "--threads", "2", "--seed",
                 str(seed), "-o", spread])
            means.append(mean_luminance(spread))
        mean = sum(means) / SPREAD_RENDERS
        se = math.sqrt(sum((m - mean) ** 2 for m in means) / (SPREAD_RENDERS - 1))
        m_merged, m_other = mean_luminance(merged), mean_luminance(other)
        parts = [os.path.join(logs, f"merged.part{k}of{TASKS}.exr") for k in range(TASKS)]
        part_mean = sum(mean_luminance(p) for p in parts) / TASKS  # equal iterations per part
        # Merged and other-seed renders are independent, each with a render's standard error.
        z = abs(m_merged - m_other) / (math.sqrt(2) * se)
        print(f"mean luminance: merged {m_merged:.6f}, other seed {m_other:.6f}, standard error {se:.2e}: "
              f"{z:.2f} sigma")
        if abs(m_merged - part_mean) > 1e-4 * abs(part_mean):
            raise Failure(f"the merged mean {m_merged} is not the parts' mean {part_mean}")
        if not z < 5:
            raise Failure("the merged mean is more than 5 standard errors from the other seed's")
        ok = True
    finally:
        cluster.stop()
        if ok:
            shutil.rmtree(work, ignore_errors=True)
        else:
            print(f"files kept in {work}", file=sys.stderr)


if __name__ == "__main__":
    try:
        main(os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]))
    except Failure as e:
        print(f"FAIL: {e}", file=sys.stderr)
        sys.exit(1)
    print("the frame rendered on Slurm and merged agrees with single-machine renders")
