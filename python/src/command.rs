//! The `batstudy` command the wheel installs: the binary's own front end (`batstudy::cli`),
//! started with Python's argv. The one place of this crate that names the command line;
//! the Python API beside it calls `batstudy::operations` as the command line does.

use pyo3::prelude::*;

/// Run the command line with `argv` (program name first); returns its exit code. Used by
/// the `batstudy` command the wheel installs, so it behaves as the binary does: its own
/// Ctrl-C handling, and a closed pipe ends it quietly.
/// `command`: the words that start this same command again (the installed `batstudy`
/// script, or `python -m batstudy`), for the Slurm scripts it writes.
#[pyfunction]
#[pyo3(signature = (argv, command=None))]
pub(crate) fn cli_main(py: Python<'_>, argv: Vec<String>, command: Option<Vec<String>>) -> i32 {
    // SAFETY: this process is the command now; Python set SIGPIPE to "ignore" at start-up.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let invocation = batstudy::cli::Invocation { command };
    py.detach(|| batstudy::cli::main_exit_code_as(argv, &invocation))
}
