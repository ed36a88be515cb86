"""The operating-window advisor: the weight on bit, rpm and top drive that drill fastest
without severe stick-slip, with the margin the data allow (docs/advise.md).

Examples
--------
>>> from torsio.advice import Constraints, Region
>>> Constraints(objective="mse").to_dict()["criterion"]
'least mean MSE among points with S_SS <= 0.8'
"""

from torsio.advice.advise import AdviceInterrupted, advise
from torsio.advice.margin import Uncertainty
from torsio.advice.region import Constraints, Region
from torsio.advice.results import Advice

__all__ = ["Advice", "AdviceInterrupted", "Constraints", "Region", "Uncertainty", "advise"]
