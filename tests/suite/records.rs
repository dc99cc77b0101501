//! Record readers: the El Centro files in records/, and small K-NET, COSMOS, AT2 and
//! plain files written here, with their broken variants.

use crate::common;

use common::file as write;
use pirqa::motion::formats::{detect, format_named};
use pirqa::motion::{read_record, ReadOptions, Record};
use std::path::{Path, PathBuf};

const G: f64 = 9.81;

fn shipped(name: &str) -> PathBuf {
    Path::new("records").join(name)
}

fn read(path: &Path) -> Result<Record, String> {
    read_record(path, None, &ReadOptions::default()).map_err(|e| e.to_string())
}

#[test]
fn el_centro_peer_at2() {
    let r = read(&shipped("elcentro1940_IELC180_peer_dt0p01_g.AT2")).unwrap();
    assert_eq!(r.accel_m_s2().len(), 4000);
    assert_eq!(r.dt_s(), 0.01);
    assert!(
        (r.pga_m_s2() / G - 0.3129).abs() < 5e-5,
        "PGA {} g",
        r.pga_m_s2() / G
    );
    assert!((r.accel_m_s2()[0] / G - -0.006403182).abs() < 1e-15);
}

#[test]
fn el_centro_peknold_at2() {
    let r = read(&shipped("elcentro1940_ns_peknold_dt0p02_g.AT2")).unwrap();
    assert_eq!(r.accel_m_s2().len(), 1559);
    assert_eq!(r.dt_s(), 0.02);
    assert!(
        (r.pga_m_s2() / G - 0.3188).abs() < 5e-5,
        "PGA {} g",
        r.pga_m_s2() / G
    );
}

#[test]
fn at2_header_variants_and_broken_files() {
    let old = "PEER NGA STRONG MOTION DATABASE RECORD\nTEST, 1/1/1\nACCELERATION TIME HISTORY IN UNITS OF G\n   5    0.0100    NPTS, DT\n .1181069E-02-.2E-02 .3 -.4\n 0.5\n";
    let r = read(&write("old.at2", old)).unwrap();
    assert_eq!(r.accel_m_s2().len(), 5);
    assert!((r.accel_m_s2()[0] - 0.001181069 * G).abs() < 1e-15);
    assert!(
        (r.accel_m_s2()[1] + 0.002 * G).abs() < 1e-15,
        "touching values are split"
    );
    let cases = [
        (
            "short.at2",
            "H\nH\nH\nNPTS=    6, DT= .0100 SEC\n1 2 3\n4 5\n",
            "line 6: the data end after 5 values; NPTS on line 4 says 6",
        ),
        (
            "bad.at2",
            "H\nH\nH\nNPTS=    4, DT= .0100 SEC\n1 2 x 4\n",
            "line 5: \"x\" is not a number",
        ),
        (
            "dt0.at2",
            "H\nH\nH\nNPTS=    4, DT= 0.000 SEC\n1 2 3 4\n",
            "line 4: DT = 0",
        ),
        (
            "nan.at2",
            "H\nH\nH\nNPTS=    4, DT= .0100 SEC\n1 NaN 3 4\n",
            "line 5: \"NaN\" is not a finite number",
        ),
        (
            "nohdr.at2",
            "H\nH\nNPTS=    4, DT= .0100 SEC\n1 2 3 4\n5 6\n",
            "line 4: expected the PEER header",
        ),
    ];
    for (name, text, expect) in cases {
        let e = read_record(&write(name, text), Some("at2"), &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains(name) && e.contains(expect), "{name}: {e}");
    }
}

fn knet_text(scale: &str, freq: &str, data: &str) -> String {
    let labels = [
        ("Origin Time", "2011/03/11 14:46:00"),
        ("Lat.", "38.103"),
        ("Long.", "142.860"),
        ("Depth. (km)", "24"),
        ("Mag.", "9.0"),
        ("Station Code", "TST001"),
        ("Station Lat.", "38.7294"),
        ("Station Long.", "141.0218"),
        ("Station Height(m)", "230"),
        ("Record Time", "2011/03/11 14:46:34"),
        ("Sampling Freq(Hz)", freq),
        ("Duration Time(s)", "300"),
        ("Dir.", "N-S"),
        ("Scale Factor", scale),
        ("Max. Acc. (gal)", "2.5"),
        ("Last Correction", "2011/03/11 14:46:19"),
        ("Memo.", ""),
    ];
    let mut s: String = labels
        .iter()
        .map(|(l, v)| format!("{l:<18}{v}\n"))
        .collect();
    s.push_str(data);
    s
}

#[test]
fn knet_counts_to_gal_with_the_mean_removed() {
    // 3920/6182761 gal per count; counts 1000 ... ; mean removed.
    let data = "  1000  2000  3000  4000  5000  6000  7000  8000\n  9000\n";
    let p = write(
        "TST0011103111446.NS",
        &knet_text("3920(gal)/6182761", "100Hz", data),
    );
    assert_eq!(detect(&std::fs::read_to_string(&p).unwrap()).name(), "knet");
    let r = read(&p).unwrap();
    assert_eq!(r.dt_s(), 0.01);
    assert_eq!(r.accel_m_s2().len(), 9);
    let factor = 3920.0 / 6182761.0 * 0.01;
    assert!((r.accel_m_s2()[0] - (1000.0 - 5000.0) * factor).abs() < 1e-15);
    assert!(r.accel_m_s2().iter().sum::<f64>().abs() < 1e-12);
    assert!(r.name.contains("N-S"));
}

#[test]
fn knet_broken_headers_and_data() {
    let data = "1 2 3\n";
    let cases = [
        (
            knet_text("3920(gal)/6182761", "fast", data),
            "line 11: sampling frequency \"fast\"",
        ),
        (
            knet_text("3920/gal", "100Hz", data),
            "line 14: scale factor \"3920/gal\"",
        ),
        (
            knet_text("3920(gal)/6182761", "100Hz", "1 2 3.5\n"),
            "line 18: 3.5 is not an integer count",
        ),
        (
            knet_text("3920(gal)/6182761", "100Hz", data).replacen(
                "Scale Factor",
                "Scale Fuctor",
                1,
            ),
            "line 14: expected the K-NET header field `Scale Factor`",
        ),
    ];
    for (k, (text, expect)) in cases.iter().enumerate() {
        let name = format!("broken{k}.EW");
        let e = read_record(&write(&name, text), Some("knet"), &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains(&name) && e.contains(expect), "{e}");
    }
}

/// A COSMOS V2 file with one channel: 13 text lines, 100 integers, 100 reals (sample interval
/// 20 ms at value 62), 2 comments, then acceleration (cm/s2, 8F10.5, values touching), velocity
/// and displacement blocks.
fn cosmos_text(dt_ms: f64, acc: &[f64], npts_claimed: usize) -> String {
    let mut s =
        String::from("Corrected acceleration  (Format v01.20 with 13 text lines) Src: test\n");
    for k in 2..=13 {
        s.push_str(&format!("text header line {k}\n"));
    }
    s.push_str("  100 Integer-header values follow on  10 lines, Format= (10I8)\n");
    let mut ints = vec![-999i64; 100];
    ints[0] = 2; // V2
    ints[1] = 1; // acceleration
    ints[2] = 4; // cm/s2
    for line in ints.chunks(10) {
        s.push_str(&line.iter().map(|v| format!("{v:>8}")).collect::<String>());
        s.push('\n');
    }
    s.push_str("  100 Real-header values follow on  20 lines, Format= (5F15.6)\n");
    let mut reals = vec![-999.0f64; 100];
    reals[61] = dt_ms;
    reals[62] = dt_ms * 1e-3 * acc.len() as f64;
    for line in reals.chunks(5) {
        s.push_str(
            &line
                .iter()
                .map(|v| format!("{v:>15.6}"))
                .collect::<String>(),
        );
        s.push('\n');
    }
    s.push_str("    2 Comment line(s) follow, each starting with a \"|\":\n| processed\n| test\n");
    s.push_str(&format!("   {npts_claimed} acceleration pts, approx    1 secs, units=cm/sec2 (04), Format=(8F10.5)\n"));
    for line in acc.chunks(8) {
        s.push_str(
            &line
                .iter()
                .map(|v| format!("{v:>10.5}"))
                .collect::<String>(),
        );
        s.push('\n');
    }
    s.push_str(&format!(
        "   {} velocity     pts, approx    1 secs, units=cm/sec  (05), Format=(8F10.5)\n",
        acc.len()
    ));
    for line in acc.chunks(8) {
        s.push_str(
            &line
                .iter()
                .map(|_| format!("{:>10.5}", 0.0))
                .collect::<String>(),
        );
        s.push('\n');
    }
    s.push_str("End-of-data for Chan  1 acceleration\n");
    s
}

#[test]
fn cosmos_v2_fixed_width_values_that_touch() {
    let acc: Vec<f64> = (0..11)
        .map(|k| if k % 2 == 0 { -100.12345 } else { 250.5 })
        .collect();
    let p = write("test.v2", &cosmos_text(20.0, &acc, acc.len()));
    assert!(
        std::fs::read_to_string(&p)
            .unwrap()
            .contains("-100.12345-100.12345")
            || std::fs::read_to_string(&p)
                .unwrap()
                .contains(" 250.50000-100.12345")
    );
    assert_eq!(
        detect(&std::fs::read_to_string(&p).unwrap()).name(),
        "cosmos"
    );
    let r = read(&p).unwrap();
    assert_eq!(r.dt_s(), 0.02);
    assert_eq!(r.accel_m_s2().len(), 11);
    assert!((r.accel_m_s2()[0] + 1.0012345).abs() < 1e-15);
    assert!((r.accel_m_s2()[1] - 2.505).abs() < 1e-15);
}

#[test]
fn cosmos_broken_files() {
    let acc = vec![1.0; 8];
    let short = write("short.v2", &cosmos_text(20.0, &acc, 12));
    let e = read(&short).unwrap_err();
    assert!(e.contains("short.v2") && e.contains("acceleration"), "{e}");
    let nodt = write("nodt.v2", &cosmos_text(-999.0, &acc, 8));
    let e = read(&nodt).unwrap_err();
    assert!(
        e.contains("nodt.v2") && e.contains("value 62 (sample interval) is -999 ms"),
        "{e}"
    );
    let text = cosmos_text(20.0, &acc, 8).replace("   1.00000", "   1.0x000");
    let e = read(&write("garbled.v2", &text)).unwrap_err();
    assert!(
        e.contains("garbled.v2") && e.contains("\"1.0x000\" is not a number"),
        "{e}"
    );
}

#[test]
fn plain_files_and_formats_by_name() {
    let p = write("plain.csv", "time_s,acc_gal\n0,100\n0.005,200\n0.01,-50\n");
    let e = read(&p).unwrap_err();
    assert!(e.contains("plain.csv") && e.contains("--units"), "{e}");
    let r = read_record(
        &p,
        None,
        &ReadOptions {
            units: Some(pirqa::units::AccelUnit::Gal),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r.accel_m_s2(), vec![1.0, 2.0, -0.5]);
    for name in ["at2", "knet", "cosmos", "plain", "csv"] {
        assert!(format_named(name).is_some(), "{name}");
    }
    let e = read_record(&p, Some("sac"), &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown format \"sac\""), "{e}");
}

/// An option the record would not use, or one that contradicts what the file says, is refused
/// with what to leave out, never ignored.
#[test]
fn options_a_record_would_not_use_or_contradicts_are_refused() {
    use pirqa::units::AccelUnit;
    let with = |path: &Path, dt_s, units, component| {
        let opts = ReadOptions {
            dt_s,
            units,
            component,
        };
        read_record(path, None, &opts)
            .map(|r| r.dt_s())
            .map_err(|e| e.to_string())
    };
    let at2 = shipped("elcentro1940_IELC180_peer_dt0p01_g.AT2");
    for (e, option) in [
        (with(&at2, Some(0.02), None, None), "--record-dt"),
        (with(&at2, None, Some(AccelUnit::Gal), None), "--units"),
        (with(&at2, None, None, Some(1)), "--component"),
    ] {
        let e = e.unwrap_err();
        assert!(
            e.contains("AT2")
                && e.contains("at2 format")
                && e.contains(&format!("leave {option} out")),
            "{e}"
        );
    }
    let cosmos = write("one.v2", &cosmos_text(10.0, &[1.0, 2.0, 3.0], 3));
    let e = with(&cosmos, Some(0.01), None, None).unwrap_err();
    assert!(
        e.contains("cosmos format") && e.contains("--record-dt"),
        "{e}"
    );

    // A plain file's own header lines and the options must agree; agreeing is fine.
    let one = write("one.txt", "# units: gal\n# dt_s: 0.01\n1\n2\n3\n");
    assert_eq!(with(&one, None, Some(AccelUnit::Gal), None), Ok(0.01));
    let e = with(&one, None, Some(AccelUnit::G), None).unwrap_err();
    assert!(
        e.contains("line 1") && e.contains("says units gal, but units g"),
        "{e}"
    );
    let e = with(&one, Some(0.02), None, None).unwrap_err();
    assert!(
        e.contains("line 2") && e.contains("dt 0.01 s, but dt 0.02 s"),
        "{e}"
    );
    let e = with(&one, None, None, Some(1)).unwrap_err();
    assert!(e.contains("one column") && e.contains("--component"), "{e}");
    let timed = write(
        "timed.txt",
        "# units: gal\n# dt_s: 0.02\n0 1\n0.01 2\n0.02 3\n",
    );
    let e = with(&timed, None, None, None).unwrap_err();
    assert!(e.contains("0.02 s") && e.contains("spaced 0.01 s"), "{e}");
}
