#pragma once
// Trilinos type aliases (nalu-wind style). Include only from src/solvers/*.cpp:
// these headers are slow to compile and must not leak into the rest of Voigt.
#include <BelosLinearProblem.hpp>
#include <BelosSolverManager.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>
#include <Tpetra_Vector.hpp>
#include <Teuchos_RCP.hpp>

namespace voigt::tpetra {

using Scalar = double;
using Map = Tpetra::Map<>;
using LO = Map::local_ordinal_type;
using GO = Map::global_ordinal_type;
using Node = Map::node_type;
using Graph = Tpetra::CrsGraph<LO, GO, Node>;
using Matrix = Tpetra::CrsMatrix<Scalar, LO, GO, Node>;
using MV = Tpetra::MultiVector<Scalar, LO, GO, Node>;
using Vector = Tpetra::Vector<Scalar, LO, GO, Node>;
using Operator = Tpetra::Operator<Scalar, LO, GO, Node>;
using Problem = Belos::LinearProblem<Scalar, MV, Operator>;
using Solver = Belos::SolverManager<Scalar, MV, Operator>;
using DeviceType = Node::device_type;

} // namespace voigt::tpetra
