#pragma once
/// Module `distributed` (rad_distributed): the processes of an MPI job (`mpirun -n N radiosity
/// render|probe|sweep ...`): the inputs read once on the root and broadcast, steps that fail on
/// every process when they fail on one, and blocks of work (tiles of pixels, runs of probe
/// points) handed out as processes free up and gathered on the root (job.h; docs/cluster.md).
///
/// May use: scene (its error types), geometry, MPI (in its .cpp files only).
#include "distributed/job.h"
#include "distributed/packed_bytes.h"
