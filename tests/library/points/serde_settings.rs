//! Serde (feature `serde`) of the small values kept in a configuration, through JSON: `Torus`
//! (with and without infinite bounds on its ordinary axes), its metrics (`MinImage`), the plain
//! metrics, `OutsidePoints` and `BalanceOptions` read back equal and measuring as before; bad
//! documents (a zero or infinite period, a wrong length, a level difference out of range, an
//! unknown connectivity) refused with an error naming the axis or the value.

use orthtree::query::{
    Chebyshev, Manhattan, Metric, MinImage, OutsidePoints, SquaredEuclidean, Torus,
};
use orthtree::tree::BalanceOptions;
use orthtree::Connectivity;

fn back<T: serde::Serialize + serde::de::DeserializeOwned>(x: &T) -> T {
    serde_json::from_str(&serde_json::to_string(x).unwrap()).unwrap()
}

#[test]
fn tori_metrics_and_balance_options_round_trip() {
    let t = Torus::new([0.0, -2.0, 5.0], [10.0, 2.0, 6.0], [true, false, true]).unwrap();
    assert_eq!(back(&t), t);
    let open = Torus::new(
        [0.0, f64::NEG_INFINITY],
        [1.0, f64::INFINITY],
        [true, false],
    )
    .unwrap();
    let json = serde_json::to_string(&open).unwrap();
    assert!(json.contains("null"), "{json}");
    assert_eq!(back(&open), open);
    let m = t.squared_euclidean();
    let m2: MinImage<SquaredEuclidean, 3> = back(&m);
    assert_eq!(m2, m);
    let (a, b) = ([0.5, 1.0, 5.1], [9.5, -1.0, 5.9]);
    assert_eq!(m2.distance(&a, &b), m.distance(&a, &b));
    let m = Torus::wrapping([0.0; 2], [4.0; 2]).unwrap().chebyshev();
    assert_eq!(back(&m), m);
    assert_eq!(back(&Manhattan), Manhattan);
    assert_eq!(back(&Chebyshev), Chebyshev);
    assert_eq!(back(&SquaredEuclidean), SquaredEuclidean);
    assert_eq!(back(&OutsidePoints::Refuse), OutsidePoints::Refuse);
    for c in Connectivity::ALL {
        for k in [1, 2, BalanceOptions::MAX_LEVEL_DIFFERENCE] {
            let o = BalanceOptions::new(c).with_max_level_difference(k).unwrap();
            assert_eq!(back(&o), o);
        }
    }
}

#[test]
fn bad_tori_and_balance_options_are_refused() {
    let torus = |doc: &str| {
        serde_json::from_str::<Torus<2>>(doc)
            .unwrap_err()
            .to_string()
    };
    let e = torus(r#"{"lo":[0.0,0.0],"hi":[0.0,1.0],"wraps":[true,true]}"#);
    assert!(e.contains("axis 0"), "{e}");
    let e = torus(r#"{"lo":[0.0,null],"hi":[1.0,1.0],"wraps":[true,true]}"#);
    assert!(e.contains("axis 1 wraps but a bound is null"), "{e}");
    let e = torus(r#"{"lo":[0.0,2.0],"hi":[1.0,1.0],"wraps":[false,true]}"#);
    assert!(e.contains("axis 1"), "{e}");
    let e = torus(r#"{"lo":[0.0],"hi":[1.0,1.0],"wraps":[true,true]}"#);
    assert!(e.contains("1 values for 2 dimensions"), "{e}");
    let e = torus(r#"{"lo":[0.0,0.0],"hi":[1.0,1.0],"wraps":[true]}"#);
    assert!(e.contains("torus wraps"), "{e}");
    let e = serde_json::from_str::<MinImage<Manhattan, 1>>(
        r#"{"torus":{"lo":[1e308],"hi":[-1e308],"wraps":[true]},"metric":null}"#,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("axis 0"), "{e}");
    let balance = |doc: &str| {
        serde_json::from_str::<BalanceOptions>(doc)
            .unwrap_err()
            .to_string()
    };
    let e = balance(r#"{"connectivity":"Face","max_level_difference":0}"#);
    assert!(e.contains("max_level_difference 0"), "{e}");
    let e = balance(r#"{"connectivity":"Face","max_level_difference":33}"#);
    assert!(e.contains("33"), "{e}");
    let e = balance(r#"{"connectivity":"Diagonal","max_level_difference":1}"#);
    assert!(e.contains("Diagonal"), "{e}");
}
