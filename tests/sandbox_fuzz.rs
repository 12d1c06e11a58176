//! Broken shaders never take the program down (docs/sandbox.md, "Checking
//! a folder of shaders"): every file of the compatibility suite
//! (tests/shaders/compat) is mutated by random deletions and insertions of
//! tokens real mistakes are made of, and each mutant is compiled. None may
//! panic or hang, and every error must name the mutant's file and a line
//! of it.

mod common;

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use raysandbox::sandbox::compile;

/// Mutants per suite file.
const MUTANTS: u32 = 24;
/// Longest one compile may take before it counts as a hang (the machine
/// may be loaded; a compile takes milliseconds).
const HANG: Duration = Duration::from_secs(30);

/// A small deterministic random generator (xorshift64*): the same mutants
/// on every run.
struct Random(u64);

impl Random {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 33) as usize % n.max(1)
    }
}

/// 1 to 4 random deletions (1 to 20 characters) or insertions.
fn mutate(text: &str, random: &mut Random) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for _ in 0..1 + random.below(4) {
        let at = random.below(chars.len() + 1);
        if random.below(2) == 0 {
            let end = (at + 1 + random.below(20)).min(chars.len());
            chars.drain(at..end);
        } else {
            let insert = common::SHADER_MISTAKES[random.below(common::SHADER_MISTAKES.len())];
            chars.splice(at..at, insert.chars());
        }
    }
    chars.into_iter().collect()
}

fn suite() -> Vec<PathBuf> {
    common::shader_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/shaders/compat"))
}

#[test]
fn mutated_shaders_never_panic_or_hang_and_errors_name_the_file() {
    let mut random = Random(0x5eed_1234_abcd_0001);
    let (mut compiled, mut failed) = (0, 0);
    for path in suite() {
        let text = std::fs::read_to_string(&path).unwrap();
        let extension = path.extension().unwrap().to_string_lossy().into_owned();
        for k in 0..MUTANTS {
            let mutant = mutate(&text, &mut random);
            let name = format!("mutant{k}.{extension}");
            let (sender, receiver) = mpsc::channel();
            let (thread_name, thread_text) = (name.clone(), mutant.clone());
            std::thread::spawn(move || {
                let result =
                    std::panic::catch_unwind(|| compile(&thread_name, &thread_text).map(|_| ()));
                let _ = sender.send(result);
            });
            let result = receiver.recv_timeout(HANG).unwrap_or_else(|_| {
                panic!(
                    "{}: compiling a mutant took more than {HANG:?}:\n{mutant}",
                    path.display()
                )
            });
            let result = result.unwrap_or_else(|_| {
                panic!(
                    "{}: a mutant made the program panic:\n{mutant}",
                    path.display()
                )
            });
            match result {
                Ok(()) => compiled += 1,
                Err(e) => {
                    failed += 1;
                    assert_eq!(e.file, name, "{e}\n--- mutant:\n{mutant}");
                    assert!(
                        e.to_string().starts_with(&name),
                        "{e}\n--- mutant:\n{mutant}"
                    );
                    let lines = mutant.lines().count() as u32;
                    assert!(
                        (1..=lines.max(1)).contains(&e.line),
                        "line {} of {lines}: {e}\n--- mutant:\n{mutant}",
                        e.line
                    );
                    assert!(
                        e.to_string().starts_with(&format!("{name}:{}:", e.line)),
                        "{e}\n--- mutant:\n{mutant}"
                    );
                }
            }
        }
    }
    println!("{compiled} mutants compiled, {failed} failed, each at a line of its file");
    assert!(failed > compiled / 2, "the mutations break most files");
}
