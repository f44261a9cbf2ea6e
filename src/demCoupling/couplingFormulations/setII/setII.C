#include "setII.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace couplingFormulations
{
    defineTypeNameAndDebug(setII, 0);
    addToRunTimeSelectionTable(couplingFormulation, setII, dictionary);
}
}
