//! Runs the targets: one child process per target, fed inputs in order
//! and writing `run N` before input N, so the parent knows which input a
//! crash or a hang happened on, makes it again from its index and saves
//! it. The child catches panics and broken rules itself; the parent sees
//! what the child cannot (a stack overflow ends it by a signal) and
//! measures hangs by the child's CPU time, not by the clock: the machine
//! is shared, and a loaded clock is no sign of a hang.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, mpsc};
use std::time::{Duration, Instant};

use arbitrary::Unstructured;

use crate::inputs::random_bytes;
use crate::targets::{TARGETS, Target};

/// CPU time one input may take before it counts as a hang.
const HANG: Duration = Duration::from_secs(1);
/// Time without progress after which a child that uses no CPU counts as
/// hung too (waiting on itself); long, since a shared machine may leave a
/// child unscheduled for a while.
const STALL: Duration = Duration::from_secs(60);
/// The stack inputs run on: the 2 MiB Rust gives every thread it spawns,
/// a quarter of the main thread's, so a parser that nests close to the
/// main thread's limit is caught here first.
const STACK: usize = 2 << 20;
/// How much a target's resident memory may grow from the end of its
/// warm-up (the first tenth of its run) to its end.
const MAX_GROWTH: u64 = 32 << 20;

/// How long each target runs.
#[derive(Clone, Copy)]
enum Budget {
    /// The short fixed run of the test suite: each target's `quick` count.
    Quick,
    Count(u64),
    Seconds(f64),
}

struct Options {
    budget: Budget,
    seed: u64,
    targets: Vec<&'static Target>,
    out: PathBuf,
    /// Internal: this process is the child running the one target.
    child: bool,
    replay: Option<PathBuf>,
}

fn parse_options() -> Result<Options, String> {
    let mut options = Options {
        budget: Budget::Quick,
        seed: 1,
        targets: Vec::new(),
        out: Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz"),
        child: false,
        replay: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().ok_or(format!("{arg} needs a value"));
        match arg.as_str() {
            "--seconds" => options.budget = Budget::Seconds(number(&value()?)?),
            "--count" => options.budget = Budget::Count(number(&value()?)?),
            "--seed" => options.seed = number(&value()?)?,
            "--out" => options.out = PathBuf::from(value()?),
            "--replay" => options.replay = Some(PathBuf::from(value()?)),
            "--child" => options.child = true,
            // libtest's listing, for tools that ask every test binary.
            "--list" => {
                println!("fuzz: test");
                std::process::exit(0);
            }
            "--target" => {
                let name = value()?;
                let target = TARGETS.iter().find(|t| t.name == name).ok_or_else(|| {
                    let names: Vec<&str> = TARGETS.iter().map(|t| t.name).collect();
                    format!("no target {name}: the targets are {}", names.join(", "))
                })?;
                options.targets.push(target);
            }
            // What cargo test passes to every test binary (--nocapture,
            // --test-threads=N, a filter) is not for this one.
            other => eprintln!("fuzz: ignoring the argument {other}"),
        }
    }
    if options.targets.is_empty() {
        options.targets = TARGETS.iter().collect();
    }
    Ok(options)
}

fn number<T: std::str::FromStr>(text: &str) -> Result<T, String> {
    text.parse()
        .map_err(|_| format!("{text:?} is not a number"))
}

pub fn main() -> i32 {
    let options = match parse_options() {
        Ok(options) => options,
        Err(e) => {
            eprintln!("fuzz: {e}");
            return 2;
        }
    };
    if let Some(file) = &options.replay {
        return replay(options.targets[0], file);
    }
    if options.child {
        return child(options.targets[0], options.budget, options.seed);
    }
    let start = Instant::now();
    let mut failed = 0;
    for target in &options.targets {
        if let Err(e) = parent(target, &options) {
            println!("{}: FAILED: {e}", target.name);
            failed += 1;
        }
    }
    let passed = options.targets.len() - failed;
    println!(
        "\ntest result: {}. {passed} passed; {failed} failed; 0 ignored; 0 measured; \
         0 filtered out; finished in {:.2}s",
        if failed == 0 { "ok" } else { "FAILED" },
        start.elapsed().as_secs_f64()
    );
    i32::from(failed > 0)
}

/// Input `index` of `target` under `seed`: the same on every run.
fn input(target: &Target, seeds: &[Vec<u8>], seed: u64, index: u64) -> Vec<u8> {
    let bytes = random_bytes(target.name, seed, index);
    (target.make)(&mut Unstructured::new(&bytes), seeds).unwrap_or_default()
}

/// Runs `step` on a thread with a [`STACK`]-sized stack.
fn on_fuzz_stack<T: Send + 'static>(step: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(STACK)
        .spawn(step)
        .expect("a thread")
        .join()
        .expect("the fuzz thread catches its panics")
}

/// The last panic's message: the hook keeps it rather than print it, and
/// the child reports it with the input that caused it.
static PANIC: Mutex<String> = Mutex::new(String::new());

/// Runs one input: `Err` with what went wrong, a broken rule or a panic.
fn run_one(target: &Target, input: &[u8]) -> Result<(), String> {
    match std::panic::catch_unwind(|| (target.run)(input)) {
        Ok(result) => result,
        Err(_) => Err(format!("panic: {}", PANIC.lock().unwrap())),
    }
}

fn quiet_panics() {
    std::panic::set_hook(Box::new(|info| {
        *PANIC.lock().unwrap() = info.to_string();
    }));
}

/// The child: runs inputs 0, 1, ... of `target` until the budget is spent
/// or one fails; prints `run N` before input N, `fail N` after a failing
/// one (and why, on stderr) and at the end `done COUNT WARM END`, the
/// resident memory in bytes after the warm-up and at the end.
fn child(target: &'static Target, budget: Budget, seed: u64) -> i32 {
    quiet_panics();
    on_fuzz_stack(move || {
        let seeds = (target.seeds)();
        let mut out = std::io::stdout().lock();
        let start = Instant::now();
        let (count, seconds) = match budget {
            Budget::Quick => (target.quick, f64::INFINITY),
            Budget::Count(n) => (n, f64::INFINITY),
            Budget::Seconds(s) => (u64::MAX, s),
        };
        let mut warm = None;
        let mut index = 0;
        while index < count && start.elapsed().as_secs_f64() < seconds {
            if warm.is_none()
                && (index >= count / 10 && count != u64::MAX
                    || start.elapsed().as_secs_f64() >= seconds / 10.0)
            {
                warm = Some(resident_bytes());
            }
            writeln!(out, "run {index}").unwrap();
            let input = input(target, &seeds, seed, index);
            if let Err(e) = run_one(target, &input) {
                eprintln!("{}: input {index}: {e}", target.name);
                writeln!(out, "fail {index}").unwrap();
                return 1;
            }
            index += 1;
        }
        let end = resident_bytes();
        writeln!(out, "done {index} {} {end}", warm.unwrap_or(end)).unwrap();
        0
    })
}

/// Every input that once failed, kept as a regression test:
/// `tests/fuzz/regressions/TARGET/*`, replayed before any new input.
fn regressions(target: &Target) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz/regressions")
        .join(target.name);
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .map(|entry| entry.unwrap().path())
        .collect();
    files.sort();
    files
}

/// Replays `file` in a child process, which may crash or hang: `Err`
/// says how it failed.
fn replay_in_child(target: &Target, file: &Path) -> Result<(), String> {
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args(["--target", target.name, "--replay"])
        .arg(file)
        .stdout(Stdio::null())
        .spawn()
        .map_err(|e| format!("cannot start the child: {e}"))?;
    loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            return match status.success() {
                true => Ok(()),
                false => Err(format!("{}: {status}", file.display())),
            };
        }
        if cpu_time(child.id()) > HANG {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("{}: ran for more than {HANG:?}", file.display()));
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The parent's side of one target: replays its regressions, starts the
/// child, watches it for hangs and crashes, saves a failing input and
/// checks the memory.
fn parent(target: &'static Target, options: &Options) -> Result<(), String> {
    let regressions = regressions(target);
    for file in &regressions {
        replay_in_child(target, file)?;
    }
    if !regressions.is_empty() {
        let count = regressions.len();
        let inputs = if count == 1 { "input" } else { "inputs" };
        println!("{}: {count} regression {inputs}: ok", target.name);
    }
    let mut command = Command::new(std::env::current_exe().unwrap());
    command.args(["--child", "--target", target.name]);
    command.args(["--seed", &options.seed.to_string()]);
    match options.budget {
        Budget::Quick => {}
        Budget::Count(n) => {
            command.args(["--count", &n.to_string()]);
        }
        Budget::Seconds(s) => {
            command.args(["--seconds", &s.to_string()]);
        }
    }
    let mut child = command
        .stdout(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start the child: {e}"))?;
    let progress = Arc::new(AtomicU64::new(0));
    let (lines, reports) = mpsc::channel();
    let reader = BufReader::new(child.stdout.take().unwrap());
    let seen = progress.clone();
    std::thread::spawn(move || {
        for line in reader.lines().map_while(Result::ok) {
            match line
                .strip_prefix("run ")
                .and_then(|n| n.parse::<u64>().ok())
            {
                Some(n) => seen.store(n + 1, Ordering::Relaxed),
                None => {
                    let _ = lines.send(line);
                }
            }
        }
    });
    let start = Instant::now();
    let mut report = Vec::new();
    // The input being run, when it started and the CPU time then.
    let mut current = (0, Instant::now(), Duration::ZERO);
    loop {
        match reports.recv_timeout(Duration::from_millis(100)) {
            Ok(line) => report.push(line),
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
            Err(mpsc::RecvTimeoutError::Timeout) => {}
        }
        let now = progress.load(Ordering::Relaxed);
        let cpu = cpu_time(child.id());
        if now != current.0 {
            current = (now, Instant::now(), cpu);
        } else if now > 0 && (cpu.saturating_sub(current.2) > HANG || current.1.elapsed() > STALL) {
            let _ = child.kill();
            let _ = child.wait();
            let saved = save(target, options, now - 1)?;
            return Err(format!(
                "input {} ran for more than {HANG:?} (CPU time {:?}); saved to {}",
                now - 1,
                cpu.saturating_sub(current.2),
                saved.display()
            ));
        }
    }
    let status = child.wait().map_err(|e| e.to_string())?;
    let elapsed = start.elapsed().as_secs_f64();
    let done = report.iter().find_map(|l| l.strip_prefix("done "));
    match (status.success(), done) {
        (true, Some(done)) => check_memory(target, done, elapsed),
        _ => {
            let index = progress.load(Ordering::Relaxed).saturating_sub(1);
            let saved = save(target, options, index)?;
            let how = if report.iter().any(|l| l.starts_with("fail ")) {
                "broke a rule or panicked (the message is above)".to_string()
            } else {
                format!("crashed the process ({status})")
            };
            Err(format!("input {index} {how}; saved to {}", saved.display()))
        }
    }
}

/// Prints the executions and the memory, and fails past [`MAX_GROWTH`].
fn check_memory(target: &Target, done: &str, elapsed: f64) -> Result<(), String> {
    let numbers: Vec<u64> = done.split(' ').filter_map(|n| n.parse().ok()).collect();
    let [count, warm, end] = numbers[..] else {
        return Err(format!("the child's report {done:?} is not understood"));
    };
    let mib = |bytes: u64| bytes as f64 / f64::from(1 << 20);
    println!(
        "{}: {count} inputs in {elapsed:.1} s ({:.0}/s), resident memory {:.1} MiB after \
         the warm-up, {:.1} MiB at the end: ok",
        target.name,
        count as f64 / elapsed,
        mib(warm),
        mib(end)
    );
    if end > warm + MAX_GROWTH {
        return Err(format!(
            "resident memory grew by {:.1} MiB, more than {:.0} MiB",
            mib(end - warm),
            mib(MAX_GROWTH)
        ));
    }
    Ok(())
}

/// Makes input `index` again and writes it to the output folder.
fn save(target: &Target, options: &Options, index: u64) -> Result<PathBuf, String> {
    let seeds = (target.seeds)();
    let bytes = input(target, &seeds, options.seed, index);
    std::fs::create_dir_all(&options.out).map_err(|e| e.to_string())?;
    let name = format!(
        "{}-seed{}-{index}.{}",
        target.name, options.seed, target.extension
    );
    let path = options.out.join(name);
    std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    println!(
        "{}: replay with: scripts/fuzz --target {} --replay {}",
        target.name,
        target.name,
        path.display()
    );
    Ok(path)
}

/// Runs one saved input and says how it went (on stderr when it fails,
/// which the parent's replay of regressions shows).
fn replay(target: &'static Target, file: &Path) -> i32 {
    let input = match std::fs::read(file) {
        Ok(bytes) => bytes,
        Err(e) => {
            eprintln!("fuzz: {}: {e}", file.display());
            return 2;
        }
    };
    quiet_panics();
    let start = Instant::now();
    match on_fuzz_stack(move || run_one(target, &input)) {
        Ok(()) => {
            println!("{}: ok in {:?}", file.display(), start.elapsed());
            0
        }
        Err(e) => {
            eprintln!("{}: {e}", file.display());
            1
        }
    }
}

/// The resident memory of this process (Linux's /proc/self/statm).
fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
    let pages: u64 = statm
        .split(' ')
        .nth(1)
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    pages * 4096
}

/// The CPU time a process has used, user and system (/proc/PID/stat, in
/// the kernel's fixed 100 ticks a second).
fn cpu_time(pid: u32) -> Duration {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
    // The fields after the command name, which may hold spaces: state is
    // the first, utime and stime the 12th and 13th.
    let fields: Vec<u64> = stat
        .rsplit_once(')')
        .map(|(_, rest)| rest)
        .unwrap_or("")
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|n| n.parse().ok())
        .collect();
    Duration::from_millis(fields.iter().sum::<u64>() * 10)
}
