//! How the packager puts an archive in place (`package::replace_file`, issue 36): a
//! reader never sees a part of it, an unchanged archive is not rewritten, and the same
//! entries give the same bytes (`package::zip_bytes`).

use robofmu_fmi_build::package::{replace_file, zip_bytes};
use std::io::Read;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

fn folder(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// An archive of one entry of `size` bytes that deflate cannot shrink (xorshift).
fn archive(seed: u64, size: usize) -> Vec<u8> {
    let mut x = seed;
    let data: Vec<u8> = (0..size)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x as u8
        })
        .collect();
    zip_bytes(&[("binaries/x86_64-linux/M.so".to_string(), data)]).unwrap()
}

#[test]
fn a_reader_never_sees_a_part_of_an_archive_being_replaced() {
    // Expected: every read returns one of the two whole archives, and each opens as a
    // zip whose entry reads back completely (a truncated or half-written file fails
    // both). With std::fs::write in place of replace_file this test fails: readers
    // see the file truncated or half written.
    let dir = folder("replace-reader");
    let path = dir.join("M.fmu");
    let (small, large) = (archive(1, 1 << 10), archive(2, 4 << 20));
    replace_file(&path, &small).unwrap();
    let stop = AtomicBool::new(false);
    let (reads, seen_large) = std::thread::scope(|s| {
        let reader = s.spawn(|| {
            let (mut reads, mut seen_large) = (0, false);
            while !stop.load(Ordering::Relaxed) {
                let bytes = std::fs::read(&path).unwrap();
                assert!(
                    bytes == small || bytes == large,
                    "a partial archive: {} bytes",
                    bytes.len()
                );
                let mut zip = zip::ZipArchive::new(std::io::Cursor::new(&bytes)).unwrap();
                let mut entry = Vec::new();
                zip.by_index(0).unwrap().read_to_end(&mut entry).unwrap();
                seen_large |= bytes == large;
                reads += 1;
            }
            (reads, seen_large)
        });
        for i in 0..60 {
            replace_file(&path, if i % 2 == 0 { &large } else { &small }).unwrap();
        }
        stop.store(true, Ordering::Relaxed);
        reader.join().unwrap()
    });
    assert!(reads > 0 && seen_large, "{reads} reads");
    // Nothing is left beside the archive.
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["M.fmu"]);
}

#[test]
fn an_unchanged_archive_is_not_rewritten() {
    // Expected: the same bytes leave the file itself alone (same inode on Unix: a
    // rename would give a new one) and only move its modification time forward; other
    // bytes replace it.
    let dir = folder("replace-unchanged");
    let path = dir.join("M.fmu");
    let a = archive(3, 1000);
    assert!(replace_file(&path, &a).unwrap());
    let old = std::time::SystemTime::now() - std::time::Duration::from_secs(3600);
    std::fs::File::options()
        .append(true)
        .open(&path)
        .unwrap()
        .set_modified(old)
        .unwrap();
    let before = std::fs::metadata(&path).unwrap();
    assert!(!replace_file(&path, &a).unwrap());
    let after = std::fs::metadata(&path).unwrap();
    assert!(after.modified().unwrap() > old + std::time::Duration::from_secs(3000));
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        assert_eq!(before.ino(), after.ino());
        assert!(replace_file(&path, &archive(4, 1000)).unwrap());
        assert_ne!(std::fs::metadata(&path).unwrap().ino(), before.ino());
    }
    #[cfg(not(unix))]
    let _ = before;
    assert_eq!(std::fs::read(&path).unwrap(), archive(4, 1000));
}

#[test]
fn the_same_entries_give_the_same_archive_bytes() {
    // Expected: byte equality of two builds (fixed time stamps), so that rebuilding
    // unchanged FMUs changes no archive.
    assert_eq!(archive(5, 5000), archive(5, 5000));
    assert_ne!(archive(5, 5000), archive(6, 5000));
}
