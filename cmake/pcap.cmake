# libpcap, found once: every target that reads or writes captures links
# topkit::pcap (pkg-config's libpcap.pc, as Debian ships it).
find_package(PkgConfig REQUIRED)
pkg_check_modules(PCAP REQUIRED IMPORTED_TARGET GLOBAL libpcap)
add_library(topkit::pcap ALIAS PkgConfig::PCAP)
