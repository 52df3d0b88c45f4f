//! The tree-against-tree queries (joins) of every point tree against nested loops over the
//! points: the Euclidean joins and their parallel forms, and the joins on a periodic domain
//! against a scan over all images.

mod euclidean;
mod periodic_joins;
