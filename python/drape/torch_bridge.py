"""PyTorch bridge: drape's cloth energies and models as autograd functions.

    import drape, drape.torch_bridge as dt
    scene = drape.Scene("graphs/scenes/tshirt_coarse.yaml")
    physics = dt.SceneEnergy(scene, body_vertices)     # torch.nn.Module: x [Ng, 3] -> E(x) in J
    loss = my_loss(x) + physics(x)                      # backward gives dE/dx from drape (double precision)

    net = dt.DrapeModel(drape.Model.load())             # torch.nn.Module: body [n, Nb, 3] -> garment [n, Ng, 3]
    opt = torch.optim.Adam(net.parameters(), 1e-4)      # the parameters ARE drape's weights (shared memory)

Energies are evaluated by drape in float64 whatever the input dtype, and returned in the input's dtype.
Gradients flow to the garment vertices (energies) and to the model's weights (models); drape's graphs
do not propagate gradients to their inputs, so a model's output carries no gradient to the body.
Second derivatives do not flow through autograd: Energy.hessian gives them as a sparse matrix.
"""
import numpy as np
import torch

import drape

__all__ = ["EnergyFunction", "SceneEnergy", "ModelFunction", "DrapeModel", "energy"]


def _numpy(t):
    return t.detach().cpu().numpy()


def _require_floating(t, argument):
    """drape.ConfigError (a ValueError) for integer or boolean vertices, as the module refuses them (docs/python.md): they were
    converted to floats silently and then refused for what followed ("vertices are not in the body model's
    order", "vertex 0 and face 4 touch"), an outside check."""
    if isinstance(t, torch.Tensor) and not (t.is_floating_point()):
        raise drape.ConfigError(f"{argument}: expected floating-point vertices in metres, got {t.dtype}")
    if isinstance(t, np.ndarray) and not np.issubdtype(t.dtype, np.floating):
        raise drape.ConfigError(f"{argument}: expected floating-point vertices in metres, got {t.dtype}")


class EnergyFunction(torch.autograd.Function):
    """E(x) of one drape.Energy for garment vertices x [Ng, 3] (or a batch [n, Ng, 3] -> [n]); backward
    multiplies drape's analytic gradient dE/dx."""

    @staticmethod
    def forward(ctx, x, energy):
        _require_floating(x, "x")
        xs = _numpy(x).astype(np.float64, copy=False)
        batched = xs.ndim == 3
        values, grads = [], []
        for xi in (xs if batched else xs[None]):
            v, g = energy.value_and_gradient(xi)
            values.append(v)
            grads.append(np.ascontiguousarray(g))
        grad = torch.from_numpy(np.stack(grads) if batched else grads[0]).to(device=x.device, dtype=x.dtype)
        ctx.save_for_backward(grad)
        return torch.tensor(values if batched else values[0], dtype=x.dtype, device=x.device)

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx, grad_output):
        (grad,) = ctx.saved_tensors
        if grad.dim() == 3:
            grad_output = grad_output.view(-1, 1, 1)
        return grad_output * grad, None


def energy(x, e):
    """The value of drape.Energy `e` at x, differentiable in x."""
    return EnergyFunction.apply(x, e)


class SceneEnergy(torch.nn.Module):
    """The potential of a scene's effects (all, or `names`) on a body: forward(x) = sum of E_i(x), x [Ng, 3]
    or [n, Ng, 3]. The energies are bound once, to this body (default: the scene's own target body)."""

    def __init__(self, scene, body_vertices=None, names=None):
        super().__init__()
        self.scene = drape.Scene(scene)
        self.energies = self.scene.energies(None if body_vertices is None else _as_numpy(body_vertices))
        unknown = [n for n in (names or []) if n not in self.energies]
        if unknown:
            raise drape.ConfigError(f"names: the scene has no effect {unknown[0]!r} (it has {', '.join(self.energies)})")
        self.names = list(names or self.energies)

    def terms(self, x):
        """{effect: E_i(x)} as differentiable tensors."""
        return {n: EnergyFunction.apply(x, self.energies[n]) for n in self.names}

    def forward(self, x):
        return sum(self.terms(x).values())


def _as_numpy(a):
    return _numpy(a) if isinstance(a, torch.Tensor) else np.asarray(a)


class ModelFunction(torch.autograd.Function):
    """garment = model(body) for drape.Model `model`, differentiable in the weights passed after it (in the
    order of `names`, keys of model.weights()). Weights that are not drape's own memory are copied into the
    model before the forward."""

    @staticmethod
    def _load(model, names, weights):
        views = model.weights()
        for name, w in zip(names, weights):
            view = views[name]
            if w.data_ptr() != view.ctypes.data:
                view[...] = _numpy(w).reshape(view.shape)

    @staticmethod
    def forward(ctx, body, model, names, *weights):
        ModelFunction._load(model, names, weights)
        body_np = np.ascontiguousarray(_numpy(body), dtype=np.float32)
        garment, forward_id = model._forward(body_np)
        ctx.model, ctx.names, ctx.forward_id, ctx.body = model, names, forward_id, body_np
        # Saved as torch saves its own: a weight changed in place between this forward and its backward (an
        # optimiser step, weights()[...] *= 2) raises at backward, as torch's modules do. detach() alone
        # shares the memory, and such a gradient was neither the forward's nor the new weights' (an outside check).
        ctx.save_for_backward(*weights)
        # A change through drape's own memory (model.weights()[...] *= 2, Model.optimize) bumps no torch version
        # counter: the forward's values are kept to compare at backward (a copy of the weights, when a gradient of
        # them is asked for at all).
        ctx.snapshot = [w.detach().contiguous().clone() for w in weights] if any(ctx.needs_input_grad[3:]) else None
        return torch.from_numpy(garment).to(device=body.device)

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx, grad_garment):
        weights = ctx.saved_tensors  # (raises when one was changed in place through torch since the forward)
        if ctx.snapshot is not None:
            # The tensors given to the forward against their values then (a DrapeModel's parameters are views of
            # drape's memory, so a change through drape shows here; a copy given, as a gradient check gives, is
            # unchanged by the other forwards that load their weights into drape).
            for name, kept, w in zip(ctx.names, ctx.snapshot, weights):
                # (Bit for bit: a NaN of a diverged training equals itself here, as it does not under ==.)
                if not torch.equal(kept.view(torch.uint8), w.detach().contiguous().view(torch.uint8)):
                    raise RuntimeError(f"weight {name!r} of the drape model was changed in place between this forward and "
                                       "its backward (through drape.Model.weights() or Model.optimize): its gradient "
                                       "would be neither the forward's nor the new weights'; run the forward again")
        g = np.ascontiguousarray(_numpy(grad_garment), dtype=np.float32)
        if ctx.model._last_forward != ctx.forward_id:
            # Another forward ran since (a gradient check's perturbations): the graph is run again on this
            # forward's weights, which go back into drape's memory first.
            ModelFunction._load(ctx.model, ctx.names, weights)
        ctx.model._backward(g, ctx.forward_id, ctx.body)
        grads = ctx.model.grads()
        out = [torch.from_numpy(np.array(grads[n])).to(dtype=w.dtype) for n, w in zip(ctx.names, weights)]
        return (None, None, None, *out)


class DrapeModel(torch.nn.Module):
    """A drape.Model as a torch module: forward(body [Nb, 3] or [n, Nb, 3], float32) -> garment [.., Ng, 3].
    Its parameters are torch views of drape's weights (no copies): an optimiser stepping them changes the
    drape model, and drape.Model.predict sees the change."""

    def __init__(self, model):
        super().__init__()
        self.model = model
        self._names = list(model.weights())
        self._params = torch.nn.ParameterList(
            [torch.nn.Parameter(torch.from_numpy(w)) for w in model.weights().values()])

    def named_drape_weights(self):
        return dict(zip(self._names, self._params))

    def forward(self, body):
        _require_floating(body, "body")
        if not isinstance(body, torch.Tensor):
            body = torch.as_tensor(np.asarray(body, dtype=np.float32))
        return ModelFunction.apply(body, self.model, self._names, *self._params)
