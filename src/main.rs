fn main() {
    std::process::exit(batstudy::cli::main_exit_code());
}
