fn main() {
    // A reader that goes away (`batstudy plan S | head -1`) ends the process quietly, as
    // for any Unix filter, instead of a panic in println!. Rust ignores SIGPIPE by default.
    // SAFETY: set once, before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    std::process::exit(batstudy::cli::main_exit_code());
}
