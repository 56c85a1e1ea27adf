//! Tiles on a real scheduler: a single-node Slurm (Debian 12's `munge`, `slurmctld`, `slurmd`,
//! `slurm-client`), started here as root without systemd, every file in a temporary folder,
//! its daemons ended by their PIDs when the test ends, however it ends. A job array renders the
//! tiles of a Whitted scene and of a path-traced one (`glint render --tile N`, the index from
//! `SLURM_ARRAY_TASK_ID`), a dependent job merges them (`--dependency=afterok`), and the merged
//! image is the single render bit for bit; an array in which one task fails leaves a merge
//! (`afterany`) that fails naming the missing tile and writes nothing, and farm.md's retry of
//! that tile, with a merge after both arrays, is the single render again. docs/farm.md is the
//! recipe this follows.
//!
//! `GLINT_SKIP_SLURM=1` skips it on purpose; without Slurm (or without root) it fails saying
//! what to install.

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use glint_io::exr_file::read_exr;

use super::{TempDir, glint, text};

const BIN: &str = env!("CARGO_BIN_EXE_glint");
const INSTALL: &str = "install Slurm and MUNGE (apt-get install munge slurmctld slurmd slurm-client) and run as root, \
                       or set GLINT_SKIP_SLURM=1";

/// The daemons of the test's cluster, killed when it is dropped (also when a test panics).
struct Cluster {
    dir: PathBuf,
    conf: PathBuf,
    daemons: Vec<(&'static str, Child)>,
}

impl Drop for Cluster {
    fn drop(&mut self) {
        for (_, child) in self.daemons.iter_mut().rev() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// A free TCP port on this machine (bound and released at once).
fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0").and_then(|l| l.local_addr()).expect("a free port").port()
}

fn which(program: &str) -> bool {
    Command::new("sh").args(["-c", &format!("command -v {program}")]).output().is_ok_and(|o| o.status.success())
}

impl Cluster {
    /// munged with its own key and socket, then slurmctld and slurmd in the foreground, and
    /// waits until the node is idle.
    fn start(dir: &Path) -> Self {
        for program in ["munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo"] {
            assert!(which(program), "{program} is not installed: {INSTALL}");
        }
        let uid = Command::new("id").arg("-u").output().expect("id -u");
        assert_eq!(text(&uid.stdout).trim(), "0", "the single-node Slurm runs its daemons as root: {INSTALL}");
        let host = text(&Command::new("hostname").output().expect("hostname").stdout).trim().to_string();
        let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
        for sub in ["state", "spool"] {
            std::fs::create_dir_all(dir.join(sub)).expect("cluster folders");
        }
        let key = dir.join("munge.key");
        let mut random = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(std::fs::File::open("/dev/urandom").expect("urandom"), 1024),
            &mut random,
        )
        .expect("a random munge key");
        std::fs::write(&key, random).expect("munge key");
        std::fs::set_permissions(&key, std::os::unix::fs::PermissionsExt::from_mode(0o400)).expect("key mode");
        let socket = dir.join("munge.sock");
        let d = |name: &str| dir.join(name).display().to_string();
        let conf = dir.join("slurm.conf");
        std::fs::write(
            &conf,
            format!(
                "ClusterName=glint\nSlurmctldHost={host}\nSlurmUser=root\nSlurmdUser=root\n\
                 AuthType=auth/munge\nAuthInfo=socket={socket}\nCredType=cred/munge\n\
                 ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n\
                 StateSaveLocation={state}\nSlurmdSpoolDir={spool}\n\
                 SlurmctldPidFile={ctld_pid}\nSlurmdPidFile={d_pid}\n\
                 SlurmctldPort={ctld_port}\nSlurmdPort={d_port}\n\
                 SlurmctldLogFile={ctld_log}\nSlurmdLogFile={d_log}\n\
                 SchedulerType=sched/builtin\nSelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n\
                 AccountingStorageType=accounting_storage/none\nJobAcctGatherType=jobacct_gather/none\n\
                 JobCompType=jobcomp/none\nMpiDefault=none\nReturnToService=2\n\
                 NodeName={host} CPUs={cpus} State=UNKNOWN\n\
                 PartitionName=glint Nodes={host} Default=YES MaxTime=INFINITE State=UP\n",
                socket = socket.display(),
                state = d("state"),
                spool = d("spool"),
                ctld_pid = d("slurmctld.pid"),
                d_pid = d("slurmd.pid"),
                ctld_port = free_port(),
                d_port = free_port(),
                ctld_log = d("slurmctld.log"),
                d_log = d("slurmd.log"),
            ),
        )
        .expect("slurm.conf");
        std::fs::write(dir.join("cgroup.conf"), "CgroupPlugin=cgroup/v1\n").expect("cgroup.conf");
        let mut cluster = Cluster { dir: dir.to_owned(), conf: conf.clone(), daemons: Vec::new() };
        let spawn = |program: &str, args: &[String]| {
            let log = std::fs::File::create(dir.join(format!("{program}.out"))).expect("daemon log");
            Command::new(program)
                .args(args)
                .env("SLURM_CONF", &conf)
                .stdout(log.try_clone().expect("log"))
                .stderr(log)
                .spawn()
                .unwrap_or_else(|e| panic!("{program} did not start ({e}): {INSTALL}"))
        };
        let munged = [
            "-F".into(),
            "--force".into(),
            format!("--key-file={}", key.display()),
            format!("--socket={}", socket.display()),
            format!("--pid-file={}", d("munged.pid")),
            format!("--log-file={}", d("munged.log")),
            format!("--seed-file={}", d("munged.seed")),
        ];
        cluster.daemons.push(("munged", spawn("munged", &munged)));
        cluster.wait_for("munged's socket", || socket.exists());
        let conf_args = ["-D".to_string(), "-f".to_string(), conf.display().to_string()];
        cluster.daemons.push(("slurmctld", spawn("slurmctld", &conf_args)));
        cluster.daemons.push(("slurmd", spawn("slurmd", &conf_args)));
        cluster.wait_for("the node to be idle", || {
            cluster.client("sinfo", &["-h", "-o", "%t"]).is_some_and(|state| state.trim() == "idle")
        });
        cluster
    }

    /// A client command's stdout, or `None` when it fails.
    fn client(&self, program: &str, args: &[&str]) -> Option<String> {
        let out =
            Command::new(program).args(args).env("SLURM_CONF", &self.conf).stderr(Stdio::piped()).output().ok()?;
        out.status.success().then(|| text(&out.stdout))
    }

    /// Polls `ready` for up to a minute; on a timeout, fails with the daemons' logs.
    fn wait_for(&self, what: &str, ready: impl Fn() -> bool) {
        let start = Instant::now();
        while !ready() {
            if start.elapsed() > Duration::from_secs(60) {
                let logs: Vec<String> = ["munged.out", "slurmctld.out", "slurmd.out", "slurmctld.log", "slurmd.log"]
                    .iter()
                    .map(|f| format!("--- {f}\n{}", std::fs::read_to_string(self.dir.join(f)).unwrap_or_default()))
                    .collect();
                panic!("the single-node Slurm: no {what} after a minute\n{}", logs.join("\n"));
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// Submits with sbatch and gives the job's id.
    fn sbatch(&self, args: &[&str]) -> String {
        let out = Command::new("sbatch")
            .arg("--parsable")
            .args(args)
            .env("SLURM_CONF", &self.conf)
            .current_dir(&self.dir)
            .output()
            .expect("sbatch");
        assert!(out.status.success(), "sbatch {args:?}: {}", text(&out.stderr));
        text(&out.stdout).trim().split(';').next().unwrap_or_default().to_string()
    }

    /// Waits until the queue is empty (every job ended, or was dropped as never runnable).
    fn drain(&self) {
        self.wait_for("empty queue", || self.client("squeue", &["-h"]).is_some_and(|q| q.trim().is_empty()));
    }
}

/// The job script of an array of `count` tiles of `scene`: one `glint render --tile` per task,
/// the index from SLURM_ARRAY_TASK_ID; task `fail` (if any) exits with an error instead.
fn array_script(dir: &Path, name: &str, scene: &str, settings: &str, count: u32, fail: Option<u32>) -> PathBuf {
    let script = dir.join(format!("{name}.sh"));
    let failing = fail.map_or(String::new(), |i| format!("[ \"$SLURM_ARRAY_TASK_ID\" = {i} ] && exit 3\n"));
    std::fs::write(
        &script,
        format!(
            "#!/bin/sh\n{failing}exec {BIN} render {scene} {settings} --tile {count} -q -o {}/{name}-tile-$SLURM_ARRAY_TASK_ID.exr\n",
            dir.display()
        ),
    )
    .expect("job script");
    script
}

fn bits(path: &Path) -> Vec<u32> {
    read_exr(path).unwrap_or_else(|e| panic!("{e}")).rgb.iter().flatten().map(|v| v.to_bits()).collect()
}

#[test]
fn a_slurm_job_array_renders_tiles_whose_dependent_merge_is_the_single_render() {
    if glint_test_support::skip_requested("GLINT_SKIP_SLURM") {
        eprintln!("GLINT_SKIP_SLURM=1: the single-node Slurm test is skipped");
        return;
    }
    let dir = TempDir::new("slurm");
    let cluster = Cluster::start(&dir);
    let cases = [
        ("whitted", "whitted", "--width 48 --height 36 --spp 2", 4, None),
        ("gi", "cornell-gi", "--width 40 --height 30 --spp 4 --depth 6", 3, None),
        ("broken", "whitted", "--width 48 --height 36", 3, Some(1)),
    ];
    let mut merges = Vec::new();
    for (name, scene, settings, count, fail) in cases {
        let script = array_script(&dir, name, scene, settings, count, fail);
        let out = format!("--output={}/{name}-%A_%a.txt", dir.display());
        let array = cluster.sbatch(&[&format!("--array=0-{}", count - 1), &out, script.to_str().expect("utf-8")]);
        // The merge after the array: afterok for the good arrays; afterany for the one with a
        // failing task, so that the merge runs and says what is missing.
        let kind = if fail.is_some() { "afterany" } else { "afterok" };
        let merged = dir.join(format!("{name}-merged.exr"));
        let tiles = format!("{}/{name}-tile-*.exr", dir.display());
        let wrap = format!("{BIN} merge {tiles} -o {}", merged.display());
        let log = dir.join(format!("{name}-merge.txt"));
        let merge = cluster.sbatch(&[
            &format!("--dependency={kind}:{array}"),
            &format!("--output={}", log.display()),
            "--wrap",
            &wrap,
        ]);
        merges.push((name, scene, settings, merged, log, fail));
        if let Some(i) = fail {
            // farm.md's retry: the failed index again (here once the first merge has said what is
            // missing), and a merge after both the retry and the whole first array, which may
            // still be running when a user notices the failure.
            let fixed = array_script(&dir, name, scene, settings, count, None);
            let retry = cluster.sbatch(&[
                &format!("--array={i}"),
                &format!("--dependency=afterany:{merge}"),
                &out,
                fixed.to_str().expect("utf-8"),
            ]);
            let retried = dir.join(format!("{name}-retried.exr"));
            let log = dir.join(format!("{name}-retried-merge.txt"));
            cluster.sbatch(&[
                &format!("--dependency=afterany:{array},afterok:{retry}"),
                &format!("--output={}", log.display()),
                "--wrap",
                &format!("{BIN} merge {tiles} -o {}", retried.display()),
            ]);
            merges.push((name, scene, settings, retried, log, None));
        }
    }
    cluster.drain();
    for (name, scene, settings, merged, log, fail) in merges {
        let said =
            std::fs::read_to_string(&log).unwrap_or_else(|e| panic!("{name}: no merge log {}: {e}", log.display()));
        match fail {
            None => {
                assert!(merged.exists(), "{name}: the merge job wrote nothing:\n{said}");
                let single = dir.join(format!("{name}-single.exr"));
                let mut args = vec!["render".to_string(), scene.to_string()];
                args.extend(settings.split_whitespace().map(str::to_string));
                args.extend(["-q".into(), "-o".into(), single.display().to_string()]);
                let done = glint(&dir, args);
                assert!(done.status.success(), "{}", text(&done.stderr));
                assert_eq!(bits(&merged), bits(&single), "{name}: the merged tiles differ from the single render");
                let task_log = std::fs::read_dir(&*dir)
                    .expect("folder")
                    .filter_map(Result::ok)
                    .find(|e| {
                        e.file_name().to_string_lossy().starts_with(&format!("{name}-"))
                            && e.file_name().to_string_lossy().ends_with("_0.txt")
                    })
                    .map(|e| std::fs::read_to_string(e.path()).unwrap_or_default())
                    .unwrap_or_default();
                assert!(task_log.contains("index from SLURM_ARRAY_TASK_ID"), "{name}: task 0 said:\n{task_log}");
            }
            Some(i) => {
                assert!(!merged.exists(), "{name}: a merge with a failed tile wrote {}", merged.display());
                assert!(said.contains(&format!("tiles is missing: {i}")), "{name}: the merge said:\n{said}");
            }
        }
    }
    drop(cluster);
}
