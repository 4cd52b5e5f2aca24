// Tpetra type aliases. Heavy header: only parallel/, assembly/, solver/, run/ include it.
#pragma once
#include <Kokkos_Core.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_FECrsGraph.hpp>
#include <Tpetra_FECrsMatrix.hpp>
#include <Tpetra_FEMultiVector.hpp>

namespace stentor::la {

using SC = double;
using LO = Tpetra::Map<>::local_ordinal_type;
using GO = Tpetra::Map<>::global_ordinal_type;
using Node = Tpetra::Map<>::node_type;
using Map = Tpetra::Map<LO, GO, Node>;
using Import = Tpetra::Import<LO, GO, Node>;
using Export = Tpetra::Export<LO, GO, Node>;
using MV = Tpetra::MultiVector<SC, LO, GO, Node>;
using Vector = Tpetra::Vector<SC, LO, GO, Node>;
using CrsMatrix = Tpetra::CrsMatrix<SC, LO, GO, Node>;
using RowMatrix = Tpetra::RowMatrix<SC, LO, GO, Node>;
using Operator = Tpetra::Operator<SC, LO, GO, Node>;
using FEGraph = Tpetra::FECrsGraph<LO, GO, Node>;
using FEMatrix = Tpetra::FECrsMatrix<SC, LO, GO, Node>;
using FEVector = Tpetra::FEMultiVector<SC, LO, GO, Node>;
using ExecSpace = Node::execution_space;
using Comm = Teuchos::Comm<int>;
template <class T>
using RCP = Teuchos::RCP<T>;

}  // namespace stentor::la
