//! Progress of long phases is drawn on a terminal only: with stdout a pipe (a script, CI) the
//! run prints nothing beyond its results, however large the scene.

use crate::common::{cycloid, PaperSpec, Scratch};

/// A scene of 500,000 crank angles (a bar is drawn for 200,000 and more on a terminal): run
/// with stdout and stderr piped, stderr stays empty and stdout holds only the results.
#[test]
fn a_large_scene_prints_no_progress_into_a_pipe() {
    let dir = Scratch::new("progress");
    let spec = PaperSpec::new().scenes(
        "  - name: long\n    output_torque_nm: 10.0\n    \
         crank: { from_deg: 0.0, to_deg: 3600.0, steps: 500000 }\n    \
         effects: [clearance]\n",
    );
    dir.write("s.yaml", spec.text());
    let run = cycloid(&dir.path, &["check", "s.yaml"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
    assert_eq!(run.stderr, "");
    assert!(
        !run.stdout.contains('\r') && !run.stdout.contains('\u{1b}'),
        "{}",
        run.stdout
    );
}

/// The same run with stderr a terminal (a pseudo-terminal from util-linux `script`) and stdout
/// redirected to a file: still nothing on the terminal, because stdout is not one. With stdout
/// the terminal, the bar is drawn. (Without `script` on the machine this test says so and
/// checks nothing more.)
#[test]
fn the_bar_follows_stdout_being_a_terminal() {
    if std::process::Command::new("script")
        .arg("--version")
        .output()
        .is_err()
    {
        eprintln!("util-linux `script` not found: pseudo-terminal part skipped");
        return;
    }
    let dir = Scratch::new("progress-tty");
    let spec = PaperSpec::new().scenes(
        "  - name: long\n    output_torque_nm: 10.0\n    \
         crank: { from_deg: 0.0, to_deg: 36000.0, steps: 1000000 }\n    \
         effects: [clearance]\n",
    );
    dir.write("s.yaml", spec.text());
    let binary = env!("CARGO_BIN_EXE_cycloid");
    let on_tty = |command: &str| {
        let out = std::process::Command::new("script")
            .args(["-qec", command, "/dev/null"])
            .current_dir(&dir.path)
            .output()
            .unwrap();
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let piped = on_tty(&format!("{binary} check s.yaml > out.txt"));
    assert!(!piped.contains("crank angles"), "{piped}");
    assert!(dir.read("out.txt").contains("headline results"));
    let shown = on_tty(&format!("{binary} check s.yaml"));
    assert!(shown.contains("solving the scenes"), "{shown}");
}
