fn main() {
    println!("rtw-scan: in progress");
}
