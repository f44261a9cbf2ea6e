#include "setI.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace couplingFormulations
{
    defineTypeNameAndDebug(setI, 0);
    addToRunTimeSelectionTable(couplingFormulation, setI, dictionary);
}
}
